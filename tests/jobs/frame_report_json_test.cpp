// One JSON form per reported type (docs/formats.md, "Reports"): a frame's FrameReport, a
// frames.json record built on it and a timed run's Timing, key by key with exact values.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "jobs/render_job.h"
#include "jobs/timing.h"
#include "render/frame_report.h"

namespace {

using nlohmann::json;

tspgl::FrameReport sample_report() {
  tspgl::FrameReport r;
  r.step = 3;
  r.spans_lo = 2, r.spans_hi = 5;
  r.shown_lo = 3, r.shown_hi = 4;
  r.ms = 12.5, r.traversal_ms = 1.25, r.slicing_ms = 2.5, r.upload_ms = 3.75, r.draw_ms = 5;
  r.step_multiplier = 1.5;
  r.class_percent = {10, 20, 30, 35, 5};
  r.bytes_uploaded = 4096, r.textures_resident = 7, r.texture_bytes = 8192;
  r.polygons = 11, r.boxes = 13, r.fragments = 17, r.redrawn_percent = 40;
  r.backend = "cpu", r.backend_note = "why";
  r.samples = 19, r.dense = true, r.deferred_textures = 2, r.bytes_stitched = 23;
  return r;
}

TEST(FrameReportJson, EveryFieldUnderItsOneKey) {
  const json j = sample_report();
  const json want = {{"step", 3},
                     {"ms", 12.5},
                     {"traversal_ms", 1.25},
                     {"slicing_ms", 2.5},
                     {"upload_ms", 3.75},
                     {"draw_ms", 5.0},
                     {"bytes_uploaded", 4096},
                     {"bytes_stitched", 23},
                     {"textures_resident", 7},
                     {"texture_bytes", 8192},
                     {"deferred_textures", 2},
                     {"polygons", 11},
                     {"boxes", 13},
                     {"fragments", 17},
                     {"redrawn_percent", 40.0},
                     {"dense", true},
                     {"caster", "cpu"},
                     {"caster_note", "why"},
                     {"samples", 19},
                     {"step_multiplier", 1.5},
                     {"steps_merged", {2, 5}},
                     {"steps_shown", {3, 4}},
                     {"not_rendered", 10.0},
                     {"untextured", 20.0},
                     {"reused_texture", 30.0},
                     {"new_texture", 35.0},
                     {"clipped", 5.0}};
  EXPECT_EQ(j, want) << j.dump(1);
  tspgl::FrameReport gl = sample_report();
  gl.backend_note.clear();
  EXPECT_FALSE(json(gl).contains("caster_note"));  // only when GL drew a frame asked of the CPU
}

TEST(FrameReportJson, AFramesJsonRecordHoldsItsReportUnchanged) {
  tspgl::FrameRecord f;
  f.report = sample_report();
  f.pass = 2;
  const json j = f, report = f.report;
  for (const auto& [key, value] : report.items())
    EXPECT_EQ(j.at(key), value) << key;
  EXPECT_EQ(j.at("pass"), 2);
}

TEST(FrameReportJson, TimingUnderBenchAndDemoKeys) {
  tspgl::Timing t;
  t.median_ms = 4, t.first_pass_median_ms = 6, t.metric_ms = 1;
  t.steps = {0, 1};
  t.step_ms = {3.5, 4.5};
  t.classes = {25, 25, 25, 25};
  t.bytes_uploaded = 1024;
  t.renderer = "llvmpipe";
  const json want = {{"median_ms", 4.0},        {"first_pass_median_ms", 6.0},
                     {"metric_ms", 1.0},        {"steps", {0, 1}},
                     {"step_ms", {3.5, 4.5}},   {"bytes_uploaded_per_frame", 1024.0},
                     {"not_rendered", 25.0},    {"untextured", 25.0},
                     {"reused_texture", 25.0},  {"new_texture", 25.0}};
  EXPECT_EQ(json(t), want) << json(t).dump(1);
}

TEST(FrameReportJson, TimingOfAResultSummarisesItsLastPass) {
  tspgl::RenderJobResult r;
  r.metric_ms = 2;
  r.renderer = "gl";
  for (int pass : {1, 2})
    for (int step : {0, 1}) {
      tspgl::FrameRecord f;
      f.pass = pass;
      f.report.step = step;
      f.report.ms = pass * 10 + step;  // pass 1: 10, 11; pass 2: 20, 21
      f.report.class_percent = {double(step) * 50, 100 - double(step) * 50, 0, 0, 0};
      f.report.bytes_uploaded = pass == 2 ? 100 * (step + 1) : 0;
      r.frames.push_back(f);
    }
  const tspgl::Timing t = tspgl::timing_of(r, 2);
  EXPECT_EQ(t.median_ms, 21);  // (the upper median of an even count: frame_set.h)
  EXPECT_EQ(t.first_pass_median_ms, 11);
  EXPECT_EQ(t.steps, (std::vector<int>{0, 1}));
  EXPECT_EQ(t.step_ms, (std::vector<double>{20, 21}));
  EXPECT_EQ(t.classes[0], 25);
  EXPECT_EQ(t.classes[1], 75);
  EXPECT_EQ(t.bytes_uploaded, 150);
  EXPECT_EQ(t.metric_ms, 2);
  EXPECT_EQ(t.renderer, "gl");
}

}  // namespace
