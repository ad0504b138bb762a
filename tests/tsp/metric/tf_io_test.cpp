#include "tsp/metric/tf_io.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "support/paths.h"
#include "tsp/core/error.h"

namespace tsp {
namespace {

std::string write(const std::string& name, const std::string& text) {
  auto p = tsptest::temp_dir() / name;
  std::ofstream(p) << text;
  return p.string();
}

// Expects a FormatError whose message names the file and contains `key`.
void expect_format_error(const std::string& text, const std::string& key) {
  std::string path = write("bad.json", text);
  try {
    load_transfer_function(path, 16);
    ADD_FAILURE() << "no error for " << text;
  } catch (const FormatError& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find(path), std::string::npos) << msg;
    EXPECT_NE(msg.find(key), std::string::npos) << msg;
  }
}

TEST(TfIo, OurJsonIsPiecewiseLinearInDataUnits) {
  std::string path = write("tf.json", R"({"range": [10, 20],
      "points": [[12, 0, 0, 0, 0], [16, 1, 0.5, 0.25, 1]]})");
  TransferFunction tf = load_transfer_function(path, 10);  // centres 10.5, 11.5, ...
  EXPECT_EQ(tf.size(), 10);
  EXPECT_EQ(tf.domain(), (ValueRange{10, 20}));
  for (int j = 0; j < 10; ++j) {
    double t = std::clamp((10.5 + j - 12) / 4, 0.0, 1.0);
    EXPECT_NEAR(tf.entry(j).r, t, 1e-6);
    EXPECT_NEAR(tf.entry(j).g, 0.5 * t, 1e-6);
    EXPECT_NEAR(tf.entry(j).b, 0.25 * t, 1e-6);
    EXPECT_NEAR(tf.entry(j).a, t, 1e-6);
  }
}

TEST(TfIo, SaveThenLoadReproducesTheTable) {
  TransferFunction tf = preset_transfer_function("sparse", {-5, 5}, 64);
  std::string path = (tsptest::temp_dir() / "saved.json").string();
  save_transfer_function(tf, path);
  TransferFunction back = load_transfer_function(path, 64);
  EXPECT_EQ(back.domain(), tf.domain());
  for (int j = 0; j < 64; ++j) {
    EXPECT_NEAR(back.entry(j).a, tf.entry(j).a, 1e-6);
    EXPECT_NEAR(back.entry(j).r, tf.entry(j).r, 1e-6);
  }
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
}

TEST(TfIo, ParaViewPresetWithOpacityCurve) {
  // As ParaView's "Save as preset" writes it: a list of presets, flat RGBPoints (x r g b) and
  // an opacity curve Points (x alpha midpoint sharpness), in data units.
  std::string path = write("pv.json", R"([{
      "ColorSpace": "Diverging", "Name": "Cool to Warm", "NanColor": [1, 1, 0],
      "RGBPoints": [0, 0.23, 0.299, 0.754,  50, 0.865, 0.865, 0.865,  100, 0.706, 0.016, 0.15],
      "Points": [0, 0, 0.5, 0,  40, 0, 0.5, 0,  100, 0.8, 0.5, 0]}])");
  TransferFunction tf = load_transfer_function(path, 100);  // centres 0.5, 1.5, ...
  EXPECT_EQ(tf.domain(), (ValueRange{0, 100}));
  // Colour: linear between the RGB points.
  EXPECT_NEAR(tf.entry(0).r, 0.23 + (0.865 - 0.23) * 0.5 / 50, 1e-5);
  EXPECT_NEAR(tf.entry(75).g, 0.865 + (0.016 - 0.865) * 25.5 / 50, 1e-5);
  // Opacity: 0 below 40, then linear to 0.8 at 100.
  EXPECT_FLOAT_EQ(tf.entry(39).a, 0.0f);
  EXPECT_NEAR(tf.entry(70).a, 0.8 * (70.5 - 40) / 60, 1e-5);
  EXPECT_NEAR(tf.entry(99).a, 0.8 * (99.5 - 40) / 60, 1e-5);
  EXPECT_TRUE(tf.transparent(0, 39));
}

TEST(TfIo, ParaViewPresetWithoutOpacityGetsTheDefaultRamp) {
  std::string path =
      write("pv.json", R"({"Name": "gray", "RGBPoints": [-1, 0, 0, 0, 1, 1, 1, 1]})");
  TransferFunction tf = load_transfer_function(path, 4);  // centres −0.75, −0.25, 0.25, 0.75
  EXPECT_EQ(tf.domain(), (ValueRange{-1, 1}));
  EXPECT_NEAR(tf.entry(0).a, 0.125, 1e-6);
  EXPECT_NEAR(tf.entry(3).a, 0.875, 1e-6);
  EXPECT_NEAR(tf.entry(2).r, 0.625, 1e-6);
}

TEST(TfIo, MalformedFilesNameTheFileAndTheKey) {
  expect_format_error("{not json", "not valid JSON");
  expect_format_error(R"({"points": [[0, 0, 0, 0, 0]]})", "\"range\"");
  expect_format_error(R"({"range": [1], "points": [[0, 0, 0, 0, 0]]})", "\"range\"");
  expect_format_error(R"({"range": [2, 1], "points": [[0, 0, 0, 0, 0]]})", "\"range\"");
  expect_format_error(R"({"range": [0, "x"], "points": [[0, 0, 0, 0, 0]]})", "range[1]");
  expect_format_error(R"({"range": [0, 1], "points": []})", "\"points\"");
  expect_format_error(R"({"range": [0, 1], "points": [[0, 0, 0, 0]]})", "points[0]");
  expect_format_error(R"({"range": [0, 1], "points": [[0, 0, 0, 0, 0], [1, 0, 2, 0, 0]]})",
                      "points[1][2]");
  expect_format_error(R"({"RGBPoints": [0, 0, 0]})", "\"RGBPoints\"");
  expect_format_error(R"({"RGBPoints": [0, 0, 0, 0, 0, 1, 1, 1]})", "\"RGBPoints\"");  // x = 0 only
  expect_format_error(R"({"RGBPoints": [0, 0, 0, 0, 1, 1, 1.5, 1]})", "RGBPoints[6]");
  expect_format_error(R"({"RGBPoints": [0, 0, 0, 0, 1, 1, 1, 1], "Points": [0, 2, 0.5, 0]})",
                      "Points[1]");
  expect_format_error(R"([{"Name": "x"}])", "RGBPoints");
  expect_format_error(R"({"colors": []})", "neither");
}

TEST(TfIo, MissingFileIsAnIoError) {
  EXPECT_THROW(load_transfer_function((tsptest::temp_dir() / "nope.json").string()), IoError);
}

TEST(TfIo, PresetsSparseIsMostlyTransparentFilledIsNot) {
  auto names = preset_names();
  EXPECT_EQ(names.size(), 10u);  // auto (from the histogram), ours three, ParaView's six maps
  TransferFunction sparse = preset_transfer_function("sparse", {0, 1000});
  TransferFunction filled = preset_transfer_function("filled", {0, 1000});
  int sparse_clear = 0, filled_clear = 0;
  for (int j = 0; j < sparse.size(); ++j) {
    sparse_clear += sparse.entry(j).a == 0;
    filled_clear += filled.entry(j).a == 0;
  }
  EXPECT_GT(sparse_clear, sparse.size() * 3 / 4);
  EXPECT_EQ(filled_clear, 0);
  EXPECT_THROW(preset_transfer_function("nope", {0, 1}), UsageError);
  TransferFunction viaarg = transfer_function_from_arg("preset:filled", {0, 1000});
  EXPECT_EQ(viaarg.entry(100), filled.entry(100));
}

TEST(TfIo, ParaViewCommonMapsAreBuiltIn) {
  // Each map's published end colours, with ParaView's linear opacity (0 low, 1 high).
  struct End {
    const char* name;
    float lo[3], hi[3];
  };
  const End ends[] = {{"viridis", {0.267f, 0.005f, 0.329f}, {0.992f, 0.906f, 0.145f}},
                      {"inferno", {0.0f, 0.0f, 0.016f}, {0.988f, 1.0f, 0.643f}},
                      {"cool-to-warm", {0.230f, 0.299f, 0.754f}, {0.706f, 0.016f, 0.150f}},
                      {"jet", {0, 0, 0.5625f}, {0.5f, 0, 0}},
                      {"grayscale", {0, 0, 0}, {1, 1, 1}},
                      {"rainbow-uniform", {0, 0, 1}, {1, 0, 0}}};
  const std::vector<std::string> names = preset_names();
  for (const End& e : ends) {
    SCOPED_TRACE(e.name);
    EXPECT_NE(std::find(names.begin(), names.end(), e.name), names.end());
    const TransferFunction tf = preset_transfer_function(e.name, {10, 20}, 1024);
    const Rgba lo = tf.lookup(10), hi = tf.lookup(20);
    EXPECT_NEAR(lo.r, e.lo[0], 2e-3);
    EXPECT_NEAR(lo.g, e.lo[1], 2e-3);
    EXPECT_NEAR(lo.b, e.lo[2], 2e-3);
    EXPECT_NEAR(hi.r, e.hi[0], 2e-3);
    EXPECT_NEAR(hi.b, e.hi[2], 2e-3);
    EXPECT_NEAR(lo.a, 0, 2e-3);
    EXPECT_NEAR(hi.a, 1, 2e-3);
    EXPECT_NEAR(tf.lookup(15).a, 0.5, 0.01);  // the linear ramp
  }
}

// --tf-range histogram: the 1st to 99th percentile of a histogram, against hand-worked cases.
TEST(TfIo, HistogramRangeIsTheCentralNinetyEightPercent) {
  EXPECT_EQ(parse_tf_range("histogram").mode, TfRangeChoice::Mode::histogram);
  // 100 samples spread evenly over 4 bins of [0, 8): 25 per bin of width 2. The 1st percentile
  // is 1 sample into bin 0: 0 + 2·(1/25) = 0.08; the 99th, 99 samples: 24 into bin 3: 6 + 2·24/25.
  const std::vector<std::uint64_t> even{25, 25, 25, 25};
  const ValueRange r = histogram_range(even, {0, 8});
  EXPECT_NEAR(r.lo, 0.08, 1e-12);
  EXPECT_NEAR(r.hi, 6 + 2 * 24.0 / 25, 1e-12);
  // A spike: 9 900 samples in bin 1 of 10 over [0, 100), 50 in bin 0 and 50 in bin 9 (the
  // extremes that set the range). The range shrinks to bin 1: [10, 20].
  std::vector<std::uint64_t> spike(10, 0);
  spike[0] = 50;
  spike[1] = 9900;
  spike[9] = 50;
  const ValueRange s = histogram_range(spike, {0, 100});
  EXPECT_NEAR(s.lo, 10 + 10 * (100 - 50) / 9900.0, 1e-9);  // 100 samples in: 50 into bin 1
  EXPECT_NEAR(s.hi, 10 + 10 * (9900 - 50 - 0.0) / 9900.0 + 0.0, 1e-9);  // 9 900 in: 9 850 into bin 1
  // Degenerate histograms keep the value range; tf_domain_of uses the histogram only when asked.
  EXPECT_EQ(histogram_range(std::vector<std::uint64_t>(4, 0), {0, 8}), (ValueRange{0, 8}));
  EXPECT_EQ(histogram_range({}, {0, 8}), (ValueRange{0, 8}));
  const std::vector<std::uint64_t> one{0, 7, 0, 0};  // every sample in one bin: still a range
  EXPECT_LT(histogram_range(one, {0, 8}).lo, histogram_range(one, {0, 8}).hi);
  EXPECT_EQ(tf_domain_of(parse_tf_range("data"), {0, 100}, spike), (ValueRange{0, 100}));
  EXPECT_EQ(tf_domain_of(parse_tf_range("histogram"), {0, 100}, spike), s);
  // step: the step's own range when it is a finite lo < hi, else the value range.
  EXPECT_EQ(parse_tf_range("step").mode, TfRangeChoice::Mode::step);
  EXPECT_EQ(parse_tf_range("visible").mode, TfRangeChoice::Mode::visible);
  EXPECT_EQ(tf_domain_of(parse_tf_range("step"), {0, 100}, spike, {20, 30}), (ValueRange{20, 30}));
  EXPECT_EQ(tf_domain_of(parse_tf_range("step"), {0, 100}, spike, {30, 30}), (ValueRange{0, 100}));
  EXPECT_EQ(tf_domain_of(parse_tf_range("data"), {0, 100}, spike, {20, 30}), (ValueRange{0, 100}));
  // A preset placed by transfer_function_from_arg over that domain has it as its own.
  const TransferFunction tf =
      transfer_function_from_arg("preset:sparse", s, kDefaultTfEntries, parse_tf_range("histogram"));
  EXPECT_NEAR(tf.domain().lo, s.lo, 1e-12);
  EXPECT_NEAR(tf.domain().hi, s.hi, 1e-12);
}

// The range words are the player's fit buttons' names ("fit to bulk", "fit to view"); the old
// words stay as aliases, and the error names the new ones.
TEST(TfIo, BulkAndViewAreTheRangeWordsHistogramAndVisibleTheirAliases) {
  EXPECT_EQ(parse_tf_range("bulk").mode, TfRangeChoice::Mode::histogram);
  EXPECT_EQ(parse_tf_range("view").mode, TfRangeChoice::Mode::visible);
  EXPECT_EQ(parse_tf_range("histogram").mode, TfRangeChoice::Mode::histogram);
  EXPECT_EQ(parse_tf_range("visible").mode, TfRangeChoice::Mode::visible);
  try {
    parse_tf_range("middle");
    FAIL() << "no error";
  } catch (const UsageError& e) {
    EXPECT_STREQ(e.what(), "--tf-range 'middle': expected auto, data, file, bulk, step, view or "
                           "LO:HI with LO < HI (histogram and visible: bulk and view)");
  }
}

TEST(TfIo, TfRangeChoicesAndRescaling) {
  EXPECT_EQ(parse_tf_range("").mode, TfRangeChoice::Mode::automatic);
  EXPECT_EQ(parse_tf_range("data").mode, TfRangeChoice::Mode::data);
  EXPECT_EQ(parse_tf_range("file").mode, TfRangeChoice::Mode::file);
  const TfRangeChoice r = parse_tf_range("-5:40");
  EXPECT_EQ(r.mode, TfRangeChoice::Mode::explicit_range);
  EXPECT_EQ(r.range.lo, -5);
  EXPECT_EQ(r.range.hi, 40);
  for (const char* bad : {"1:1", "x:2", "5", "nan:3"}) EXPECT_THROW(parse_tf_range(bad), UsageError);
  // A normalised [0, 1] map (a ParaView preset) over data in [100, 300]: stretched by default,
  // kept with --tf-range file (and then it misses the data: a warning says so).
  const std::filesystem::path f = tsptest::temp_dir() / "unit.json";
  std::ofstream(f) << R"({"range": [0, 1], "points": [[0, 0, 0, 1, 0], [1, 1, 0, 0, 1]]})";
  const ValueRange data{100, 300};
  const TransferFunction a = transfer_function_from_arg(f.string(), data);
  EXPECT_EQ(a.domain().lo, 100);
  EXPECT_EQ(a.domain().hi, 300);
  EXPECT_NEAR(a.lookup(200).a, 0.5, 0.01);
  EXPECT_TRUE(tf_range_warning(a, data).empty());
  const TransferFunction b = transfer_function_from_arg(f.string(), data, kDefaultTfEntries,
                                                        parse_tf_range("file"));
  EXPECT_EQ(b.domain().hi, 1);
  EXPECT_NE(tf_range_warning(b, data).find("--tf-range data"), std::string::npos);
  // Data inside [0, 1]: the file's range stays.
  EXPECT_EQ(transfer_function_from_arg(f.string(), {0.2, 0.7}).domain().hi, 1);
  // Explicit range; rescaled() keeps every entry's colour at the mapped position.
  const TransferFunction c = transfer_function_from_arg(f.string(), data, kDefaultTfEntries,
                                                        parse_tf_range("-1:1"));
  EXPECT_NEAR(c.lookup(0).a, 0.5, 0.01);
  const TransferFunction d = rescaled(c, {10, 30});
  for (int j = 0; j < c.size(); ++j) EXPECT_EQ(d.entry(j).a, c.entry(j).a) << j;
}

}  // namespace
}  // namespace tsp
