// The player's LOD loop (docs/player.md "Level of detail"): from what each frame shows, whether
// anything changed (interaction), and the cut the next frame asks for — the target frame rate
// while anything changes, full quality once nothing did for kIdleDelaySeconds and kIdleFrames
// frames, LaMar's filters or the playing rung's level when they apply; the focus the cut centres
// on, what the drawn cut did and when the picture got back to full quality, and the cut the
// overlay (L) shows. Window- and GL-free (the player's clock is passed in), so tests drive it
// frame by frame.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "player/player_state.h"
#include "render/frame_driver.h"
#include "tsp/frame/camera.h"
#include "tsp/lod/lod_controller.h"
#include "tsp/tree/marks.h"
#include "tsp/tree/octree.h"

namespace tspplayer {

/// Seconds without a change (view, step, TF, playback) after which the LOD cut refines to full
/// quality.
inline constexpr double kIdleDelaySeconds = 0.25;
/// Frames without a change before the cut refines (with kIdleDelaySeconds).
inline constexpr int kIdleFrames = 2;
/// Splits per frame while refining when idle (a whole 64³ series is full in a frame or two).
inline constexpr int kIdleSplitsPerFrame = 64;

/// What a frame shows beyond the state, for the LOD loop.
struct LodFrameInput {
  std::uint64_t tf_version = 0;     ///< the TF's version (an edit is a change)
  std::uint64_t probe_version = 0;  ///< the probes' version (an edit is a change)
  /// Playing at a quality target: the rung's LOD level drawn everywhere (0: full resolution).
  int rung_level = 0;
  /// A pause alone is no change (the last playing frame is refined, not replaced by a coarse
  /// cut); false: as before issue 47 (TSPPLAY_REFINE_BY_CUT).
  bool pause_keeps_picture = true;
};

/// The loop's state from frame to frame.
class LodLoop {
 public:
  /// The cut the frame at now_s asks for, given what it shows (s and in). Never throws.
  tspgl::LodSpec next(const PlayerState& s, const LodFrameInput& in, double now_s);
  /// The frame's whole time and its render share (ms): the rest (UI, swap) is taken off the
  /// target. Never throws.
  void measured(double render_ms, double frame_ms);
  /// Centres the cut on p from the next frame on; a change at now_s. Never throws.
  void focus_on(const std::array<double, 3>& p, double now_s) {
    focus_ = p;
    last_change_s_ = now_s;
  }
  /// No centre of attention (a new file). Never throws.
  void clear_focus() { focus_.reset(); }
  /// The cut's centre of attention (double-click), in voxels; none: the view's centre.
  const std::optional<std::array<double, 3>>& focus() const { return focus_; }
  /// Keeps what the frame's cut did (none: no cut was drawn). Never throws.
  void drawn(const std::optional<tsp::LodFrameStats>& stats) {
    stats_ = stats.value_or(tsp::LodFrameStats{});
  }
  /// The last drawn frame's cut (zeros when none).
  const tsp::LodFrameStats& stats() const { return stats_; }
  /// True when the last cut is full quality: refining, no node with any error, full render size.
  bool cut_full_quality() const {
    return refining_ && stats_.max_error == 0 && stats_.render_scale == 1;
  }
  /// Whether the picture drawn at now_s is at full quality: the first full one after a change
  /// sets full_quality_after_s(), one that is not clears it. Never throws.
  void note_quality(bool full, double now_s);
  /// Seconds from the last change to the first full-quality frame (−1: not there yet).
  double full_quality_after_s() const { return full_quality_after_s_; }
  /// Keeps the cut the frame drew for the overlay (empty stops: every leaf). Never throws but
  /// bad_alloc.
  void keep_cut(tsp::LodStops stops) { drawn_stops_.assign(stops.begin(), stops.end()); }
  /// The cut kept by keep_cut (empty: every leaf).
  const std::vector<tsp::LodStop>& drawn_cut() const { return drawn_stops_; }

  /// The last frame's step was not shown after all (the player dropped it for a Space press):
  /// the step on screen is step, so a pause there is no change. Never throws.
  void take_back_step(int step) { seen_.step = step; }
  /// True when the last next() refines to full quality (idle).
  bool refining() const { return refining_; }
  /// True when the last next() saw a change (or playback).
  bool changed() const { return changed_; }
  /// True when the last next() saw playback pause and nothing else change.
  bool paused_now() const { return paused_now_; }
  /// The render-time target of the last interacting frame (ms).
  double target_ms() const { return target_ms_; }
  /// The frame's time outside rendering, smoothed (ms).
  double overhead_ms() const { return overhead_ms_; }
  /// When the last change was seen (the caller's clock, s).
  double last_change_s() const { return last_change_s_; }

 private:
  struct Seen {
    tsp::CameraParams camera;
    int step = -1;
    std::uint64_t tf_version = ~std::uint64_t(0);
    std::uint64_t probe_version = ~std::uint64_t(0);
    bool playing = false;
    bool operator==(const Seen&) const = default;
  } seen_;
  double last_change_s_ = 0;
  int frames_since_change_ = 0;
  double overhead_ms_ = 0;
  double target_ms_ = 0;
  bool refining_ = false, changed_ = false, paused_now_ = false;
  std::optional<std::array<double, 3>> focus_;
  tsp::LodFrameStats stats_;
  double full_quality_after_s_ = -1;
  std::vector<tsp::LodStop> drawn_stops_;
};

/// True when node id of o is drawn by the cut stops (empty: every leaf). Never throws.
bool in_cut(const tsp::Octree& o, const std::vector<tsp::LodStop>& stops, int id);

/// What the cut overlay's caption says of the cut stops of o: "LOD cut: 8 nodes, full
/// resolution (level 0)" for every leaf (empty stops), else "LOD cut: 9 nodes, by level 0:8
/// 1:1". Never throws but bad_alloc.
std::string cut_text(const tsp::Octree& o, const std::vector<tsp::LodStop>& stops);

/// The LOD focus a click at window pixel (x, y) of cam asks for: the point of the view ray there
/// at the depth of the centre of a dims volume, in voxels (kept between the near and far
/// planes). Never throws.
std::array<double, 3> focus_at(const tsp::Camera& cam, tsp::Dims dims, double x, double y);

}  // namespace tspplayer
