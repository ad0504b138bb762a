// No popping (issue 47 item 2; docs/player.md "Level of detail"): once the picture settles — a
// pause, or nothing changed for a while after the view, step, TF or probes did — it is refined
// at full resolution in bands (render/tile_refinement.h) drawn over a picture within the quality
// target: the last playing frame after a pause (the tuned rung, within the target), or else the
// fastest tuned rung within the target drawn whole, or, with no such rung, the whole picture at
// full quality in one frame. Every frame shown meanwhile is a per-pixel mix of that picture and
// the full-quality one, so it is never further from full quality than the picture under it. A
// coarser LOD cut is never drawn after a pause. The LOD status line says which of these the last
// frame drew, and its time; `capture` writes each frame as drawn.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "player/player_app.h"
#include "tsp/core/error.h"
#include "tsp/report/image.h"

namespace tspplayer {

namespace {
// The rung drawn whole under the bands after a change has a mean ΔE over the tuning's probe
// steps of at most this share of the target: the probes saw one view, and at others a rung
// measured up to 1.4 × its probe ΔE (docs/results.md).
constexpr double kRefineBaseMargin = 0.5;
}  // namespace

bool refine_by_cut() {
  static const bool cut = std::getenv("TSPPLAY_REFINE_BY_CUT") != nullptr;
  return cut;
}

const tspgl::TunedRung* PlayerApp::base_rung() const {
  const std::vector<tspgl::TunedRung>& tuned = rungs_.ladder();
  if (state_.quality <= 0 || tuned.empty() || !(tuning_.tuned_for() == tune_key())) return nullptr;
  const tspgl::TunedRung* best = nullptr;
  for (std::size_t i = 1; i < tuned.size(); ++i) {
    const tspgl::TunedRung& r = tuned[i];
    if (r.mean_de <= kRefineBaseMargin * state_.quality && r.ms < tuned[0].ms &&
        (!best || r.ms < best->ms))
      best = &r;
  }
  return best;
}

bool PlayerApp::refine_draw(double now_s, tspgl::FrameRequest& request, tspgl::DrawnFrame& drawn) {
  (void)now_s;
  const bool applies = !refine_by_cut() && state_.lod_on && state_.lod_filter.kind == tsp::LodFilter::error &&
                       !state_.playing && !(mesh_surface && request.settings.surface);
  // Another renderer (a field switch, File > Open, a cache change) is a change too: its
  // picture is not the one the bands were drawn over.
  const bool new_renderer = &viewer_->renderer() != refine_renderer_;
  if (new_renderer) {
    full_driver_.reset();
    refine_renderer_ = &viewer_->renderer();
  }
  if (!applies || lod_loop_.changed() || new_renderer) {
    refine_on_ = false;
    bands_.stop();
    return false;
  }
  const tsp::CameraParams& view = request.camera->params();
  const bool no_target = state_.quality <= 0;
  if (!refine_on_) {
    // After a pause the last playing frame is on screen: when it was within the target, the
    // bands are drawn over it. Otherwise (or once settled after a change) over the fastest
    // tuned rung within the target, or with none the whole picture at once.
    whole_ = false;
    if (lod_loop_.paused_now() && (was_within_ || no_target)) {
      base_ = "the last playing frame";
      base_pending_ = false;
    } else if (lod_loop_.paused_now() || lod_loop_.refining()) {
      const tspgl::TunedRung* r = base_rung();
      base_pending_ = r != nullptr;
      whole_ = !r && !no_target;
      base_ = r ? std::string("rung '") + r->rung.name + "'"
                : no_target ? "the last frame (no quality target)"
                            : "nothing: the whole picture in one frame (no tuned rung within the "
                              "target at this size)";
    } else {
      return false;
    }
    refine_on_ = true;
    refine_frames_ = 0;
    uploading_ = !whole_;
    bands_.start(view.width, view.height);
  }
  ++refine_frames_;
  if (!full_driver_) full_driver_ = std::make_unique<tspgl::FrameDriver>(viewer_->renderer());
  tspgl::FrameDriver& fd = *full_driver_;
  stage_ = "refining";
  if (base_pending_) {  // the fastest rung within the target, whole, under the bands
    const tspgl::TunedRung& r = *base_rung();
    request.settings = tspgl::rung_settings(request.settings, r.rung);
    request.settings.upload_budget = 0;  // drawn whole: never with flat blocks
    tspgl::LodSpec spec;
    if (r.rung.lod_level > 0) {
      spec.mode = tspgl::LodMode::fixed;
      spec.level = r.rung.lod_level;
    }
    fd.set_lod(spec);
    drawn = fd.draw(request);
    fd.set_lod({});
    base_pending_ = false;
    within_ = true;
    return true;
  }
  fd.set_lod({});
  if (!bands_.active()) {  // done: full quality (partial-image reuse redraws nothing)
    drawn = fd.draw(request);
    stage_ = "full";
    within_ = true;
    return true;
  }
  // First the textures the full picture needs, within the upload budget a frame, drawing
  // nothing (the picture stays): a band is never drawn flat in a brick's mean colour, and no
  // frame stalls on a whole step's uploads.
  if (uploading_) {
    part_.rects.clear();
    part_.first = part_.completes = false;
    request.part = &part_;
    drawn = fd.draw(request);
    request.part = nullptr;
    uploading_ = !drawn.report.complete();
    within_ = true;
    return true;
  }
  request.settings.upload_budget = 0;  // (all resident now)
  const bool first = bands_.bands_drawn() == 0;
  const double budget_ms =
      std::max(1.0, 1000.0 / std::max(1.f, state_.target_fps) - lod_loop_.overhead_ms());
  part_.rects = bands_.next(whole_ ? 1e300 : budget_ms);
  part_.first = first;
  part_.completes = !bands_.active();
  request.part = &part_;
  drawn = fd.draw(request);
  request.part = nullptr;
  bands_.drawn(drawn.report.ms);
  if (drawn.report.partial_stale) {  // drawn with other settings than the bands before: again
    bands_.start(view.width, view.height);
    uploading_ = true;
    base_ = "a picture drawn with other settings";
    within_ = no_target;
    return true;
  }
  if (!bands_.active()) stage_ = "full";
  within_ = true;
  return true;
}

void PlayerApp::cut_drawn(bool rung) {
  const bool no_target = state_.quality <= 0;
  if (!state_.lod_on) {
    stage_ = "off";
    within_ = true;
  } else if (state_.playing) {
    stage_ = "playing";
    within_ = no_target || (rung && rungs_.choice().within_quality);
  } else {
    stage_ = "interacting";
    within_ = no_target || state_.lod_filter.kind != tsp::LodFilter::error;
  }
}

std::string PlayerApp::lod_line() const {
  char line[320];
  const double ms = last.ms;
  const tsp::LodFrameStats& lod_stats = lod_loop_.stats();
  if (stage_ == "off") {
    std::snprintf(line, sizeof line, "LOD off: full resolution every frame (last frame %.0f ms)", ms);
  } else if (stage_ == "playing") {
    const tspgl::Rung* r = rung_drawn();
    std::snprintf(line, sizeof line, "playing %s (last frame %.0f ms)",
                  r ? (std::string("rung '") + r->name + "'").c_str() : "with the LOD cut at the step's time", ms);
  } else if (stage_ == "refining" && uploading_) {
    std::snprintf(line, sizeof line,
                  "refining: uploading the full picture's textures, %lld left, over %s (last "
                  "frame %.0f ms)",
                  static_cast<long long>(last.deferred_textures), base_.c_str(), ms);
  } else if (stage_ == "refining") {
    std::snprintf(line, sizeof line,
                  "refining at full resolution: %d of %d bands drawn over %s (last frame %.0f ms)",
                  bands_.bands_drawn(), bands_.bands(), base_.c_str(), ms);
  } else if (stage_ == "full") {
    std::snprintf(line, sizeof line, "full quality (last frame %.0f ms, %.2f s after the last change)",
                  ms, lod_loop_.full_quality_after_s());
  } else if (lod_stats.splats > 0) {
    std::snprintf(line, sizeof line,
                  "LOD aiming at %.0f ms with %d splats (minimum %.0f px); last frame %.0f ms%s",
                  lod_loop_.target_ms(), lod_stats.splats, lod_stats.splat_px, ms,
                  ms > 1.5 * lod_loop_.target_ms() ? ": missing the target" : "");
  } else {
    std::string levels;
    for (std::size_t k = 0; k < lod_stats.nodes_per_level.size(); ++k)
      levels += (k ? " " : "") + std::to_string(lod_stats.nodes_per_level[k]);
    std::snprintf(line, sizeof line,
                  "LOD aiming at %.0f ms: cut %d nodes [by level %s], scale %.2f; last frame "
                  "%.0f ms%s",
                  lod_loop_.target_ms(), lod_stats.cut_size, levels.c_str(), lod_stats.render_scale,
                  ms,
                  lod_loop_.target_ms() > 0 && ms > 1.5 * lod_loop_.target_ms()
                      ? ": missing the target"
                      : "");
  }
  return line;
}

nlohmann::json PlayerApp::refine_json() const {
  return {{"stage", stage_},
          {"within_target", within_},
          {"base", base_},
          {"bands", bands_.bands()},
          {"bands_drawn", bands_.bands_drawn()},
          {"frames", refine_frames_},
          {"uploading", uploading_},
          {"line", lod_line()}};
}

void PlayerApp::capture_frame() {
  if (capture_dir_.empty()) return;
  namespace fs = std::filesystem;
  char name[32];
  std::snprintf(name, sizeof name, "frame_%04d.png", capture_count_);
  tsp::write_png((fs::path(capture_dir_) / name).string(), read_view());
  nlohmann::json j = refine_json();
  j["frame"] = capture_count_++;
  j["file"] = name;
  j["step"] = state_.step;
  j["playing"] = state_.playing;
  j["frame_report"] = last;  // as frames.json writes a frame (render/frame_report.h)
  j["view"] = {state_.camera.azimuth_deg, state_.camera.elevation_deg, state_.camera.zoom};
  j["recorded"] = recorder_ != nullptr && within_;
  std::ofstream out(fs::path(capture_dir_) / "frames.jsonl", std::ios::app);
  out << j.dump() << "\n";
  if (!out) throw tsp::IoError("capture: cannot write " + capture_dir_ + "/frames.jsonl");
}

}  // namespace tspplayer
