#include "player/lod_loop.h"

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

namespace tspplayer {

namespace {
// Smoothing of the frame's time outside rendering (UI, swap), per frame.
constexpr double kOverheadSmoothing = 0.2;
// The render share of the frame may not drop below this many milliseconds.
constexpr double kMinRenderMs = 2;
}  // namespace

tspgl::LodSpec LodLoop::next(const PlayerState& s, const LodFrameInput& in, double now_s) {
  // Any change of what is shown counts as interaction.
  const Seen now{s.camera, s.step, in.tf_version, in.probe_version, s.playing};
  // A pause alone changes nothing shown: the last playing frame stays and is refined
  // (player_refine.cpp), not replaced by a coarse cut.
  Seen playing_then = now;
  playing_then.playing = true;
  paused_now_ = seen_.playing && !s.playing && playing_then == seen_ && in.pause_keeps_picture;
  changed_ = s.playing || (!(now == seen_) && !paused_now_);
  // Playing with the view and the TF still, a frame per step is enough: the frame time may
  // follow the playback speed (5 steps/s: 200 ms) rather than the interactive target.
  const bool steady_playback = s.playing && now.camera == seen_.camera &&
                               now.tf_version == seen_.tf_version &&
                               now.probe_version == seen_.probe_version;
  if (changed_) {
    last_change_s_ = now_s;
    frames_since_change_ = 0;
  } else {
    ++frames_since_change_;
  }
  seen_ = now;
  refining_ = false;
  tspgl::LodSpec spec;
  if (!s.lod_on) return spec;
  // LaMar's selection filters: the cut follows the camera by their rule, whatever the target.
  if (s.lod_filter.kind != tsp::LodFilter::error) {
    spec.mode = tspgl::LodMode::filter;
    spec.filter = s.lod_filter;
    return spec;
  }
  // Playing at a quality target: the tuned rung's LOD level everywhere (or full resolution),
  // never a time-only cut.
  if (s.playing && s.quality > 0) {
    if (in.rung_level > 0) {
      spec.mode = tspgl::LodMode::fixed;
      spec.level = in.rung_level;
    }
    return spec;
  }
  // Idle: nothing changed for a while, and for more than one frame (a slow frame alone is not).
  refining_ = now_s - last_change_s_ >= kIdleDelaySeconds && frames_since_change_ >= kIdleFrames;
  spec.mode = tspgl::LodMode::adaptive;
  tsp::LodOptions& o = spec.options;
  o.focus = focus_;
  if (refining_) {  // full quality: every node with any error, many per frame, no time limit
    o.target_ms = 0;
    o.min_error = 0;
    o.split_limit = kIdleSplitsPerFrame;
  } else {
    const double frame_ms = std::max(1000.0 / std::max(1.f, s.target_fps),
                                     steady_playback ? 1000.0 / std::max(s.speed, 1e-3) : 0.0);
    o.target_ms = std::max(kMinRenderMs, frame_ms - overhead_ms_);
    target_ms_ = o.target_ms;
  }
  o.texture_budget = std::int64_t(s.texture_budget_mb * (1 << 20));
  o.fallback = s.splat_fallback ? tsp::LodFallback::splats : tsp::LodFallback::scale;
  return spec;
}

void LodLoop::measured(double render_ms, double frame_ms) {
  // (The driver gave the controller the render time when it drew the frame.)
  overhead_ms_ += kOverheadSmoothing * (std::max(0.0, frame_ms - render_ms) - overhead_ms_);
}

void LodLoop::note_quality(bool full, double now_s) {
  // When the picture got back to full quality after the last change.
  if (full) {
    if (full_quality_after_s_ < 0) full_quality_after_s_ = now_s - last_change_s_;
  } else {
    full_quality_after_s_ = -1;
  }
}

bool in_cut(const tsp::Octree& o, const std::vector<tsp::LodStop>& stops, int id) {
  return stops.empty() ? o.node(id).is_leaf() : stops[std::size_t(id)] != tsp::LodStop::none;
}

std::string cut_text(const tsp::Octree& o, const std::vector<tsp::LodStop>& stops) {
  std::vector<int> per_level(std::size_t(o.max_lod_level()) + 1, 0);
  int n = 0;
  for (int id = 0; id < o.size(); ++id)
    if (in_cut(o, stops, id)) {
      ++per_level[std::size_t(o.lod_level(id))];
      ++n;
    }
  std::string text = "LOD cut: " + std::to_string(n) + (n == 1 ? " node" : " nodes");
  if (stops.empty()) return text + ", full resolution (level 0)";
  text += ", by level";
  for (std::size_t l = 0; l < per_level.size(); ++l)
    if (per_level[l] > 0) text += " " + std::to_string(l) + ":" + std::to_string(per_level[l]);
  return text;
}

std::array<double, 3> focus_at(const tsp::Camera& cam, tsp::Dims d, double x, double y) {
  const glm::dmat4 inv = glm::inverse(cam.view_projection());
  const double nx = 2 * x / std::max(1, cam.params().width) - 1,
               ny = 1 - 2 * y / std::max(1, cam.params().height);
  const glm::dvec4 a = inv * glm::dvec4(nx, ny, -1, 1), b = inv * glm::dvec4(nx, ny, 1, 1);
  const glm::dvec3 p0 = glm::dvec3(a) / a.w, p1 = glm::dvec3(b) / b.w;
  const glm::dvec3 centre(0.5 * (d.x - 1), 0.5 * (d.y - 1), 0.5 * (d.z - 1));
  const auto dir = cam.direction();
  const glm::dvec3 v(dir[0], dir[1], dir[2]);
  const double denom = glm::dot(p1 - p0, v);
  const double s = std::abs(denom) > 1e-12 ? glm::dot(centre - p0, v) / denom : 0.5;
  const glm::dvec3 f = p0 + (p1 - p0) * std::clamp(s, 0.0, 1.0);
  return {f.x, f.y, f.z};
}

}  // namespace tspplayer
