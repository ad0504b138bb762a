// The player's LOD loop (docs/player.md "Level of detail"): from what each frame shows, whether
// anything changed (interaction), and the cut the next frame asks for — the target frame rate
// while anything changes, full quality once nothing did for kIdleDelaySeconds and kIdleFrames
// frames, LaMar's filters or the playing rung's level when they apply. Window- and GL-free (the
// player's clock is passed in), so tests drive it frame by frame.
#pragma once
#include <array>
#include <cstdint>
#include <optional>

#include "player/player_state.h"
#include "render/frame_driver.h"

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
  std::optional<std::array<double, 3>> focus;  ///< the cut's centre of attention
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
  /// Counts as a change at now_s (a new focus). Never throws.
  void touch(double now_s) { last_change_s_ = now_s; }

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
};

}  // namespace tspplayer
