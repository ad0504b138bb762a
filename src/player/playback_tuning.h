// The player's playback tuning (docs/player.md "Playing at a quality target"): when and for what
// the ladder of cheaper settings is probed (jobs/playback_tuner.h), its disk cache
// (jobs/tuning_cache.h), how each frame shares its time with the probe pictures, and what
// `stats` says of it. Moved out of PlayerApp (issue 44 item 4); the pacing rule is window-free.
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "jobs/playback_tuner.h"
#include "render/render_settings.h"
#include "tsp/metric/metric.h"

namespace tspplayer {

/// Milliseconds of a still window's frame the playback tuning may use (the window keeps ≥ 10
/// frames/s on top of its own frame time); playing, the time left before the next step is due.
inline constexpr double kCalibrationSliceMs = 15;
/// Step frames in a row that may hold no probe picture because none fits before the next step:
/// then one is drawn anyway (a picture longer than a step period fits no frame; at most one
/// frame in kMaxTuningWaits + 1 runs late for it).
inline constexpr int kMaxTuningWaits = 3;

/// Playing, a probe picture may take at most this share of the step period (the rest is the
/// frame's own drawing): a tuning whose first picture (full quality, the costliest) took more
/// starts again with fewer pixels (the demo's took 260–340 ms at 640×400, 8 steps/s: 125 ms).
inline constexpr double kTuningPictureShare = 0.5;
/// The smallest share of the probe's pixels (kMaxTunePixels) a tuning goes down to: 160×100.
inline constexpr double kMinProbePixelShare = 1.0 / 16;

/// What a tuning was made for: a change of any re-tunes (the camera's direction does not).
struct TuneKey {
  const void* file = nullptr;
  std::string field;
  std::uint64_t tf_version = 0;
  tsp::Metric metric = tsp::Metric::approximate;
  tspgl::RenderSettings settings;
  int width = 0, height = 0;
  bool operator==(const TuneKey&) const = default;
};

/// How a frame shares its time with the tuning's probe pictures. Playing, a picture is drawn
/// only when it is predicted to end before the next step is due, so each step is shown on time
/// (a cold tuning drew one whatever its cost every frame: frames of 260 ms at a 125 ms period
/// on the demo, for 6 s); after kMaxTuningWaits step frames without room, one is drawn anyway.
/// Still, a slice of kCalibrationSliceMs, at least one picture.
class TuningPace {
 public:
  /// The budget (ms) for this frame's pictures, 0: none this frame. playing: until_next_ms is
  /// the time left before the next step is due and step_frame whether this frame showed a new
  /// step; next_ms the next picture's predicted time (−1: unknown, drawn). Never throws.
  double budget(bool playing, double until_next_ms, bool step_frame, double next_ms);
  /// True when the last budget() was 0: the window need not draw for the tuning until a step is
  /// due.
  bool waiting() const { return waiting_; }
  /// A new tuning: no waits counted. Never throws.
  void restart() {
    waits_ = 0;
    waiting_ = false;
  }

 private:
  int waits_ = 0;  ///< step frames in a row without room
  bool waiting_ = false;
};

/// The tuning in progress and what the last one measured.
class PlaybackTuning {
 public:
  /// Makes the tuner for a tuning with pixel_share of the probe's pixels (throws tsp::Error
  /// when it cannot).
  using MakeTuner = std::function<std::unique_ptr<tspgl::PlaybackTuner>(double pixel_share)>;
  /// Starts a tuning for key at now_s (frame: frames drawn so far): the ladder kept on disk under
  /// disk_key in cache_file ("": no cache) when there is one — returned, no tuning then — else a
  /// tuner from make (kept: a tuning whose first picture is too long for the step period starts
  /// again with fewer pixels). Throws what make throws (nothing runs then).
  std::optional<std::vector<tspgl::TunedRung>> start(const TuneKey& key, nlohmann::json disk_key,
                                                     std::string cache_file, MakeTuner make,
                                                     double now_s, std::int64_t frame);
  /// Drops the tuning in progress. Never throws.
  void stop() { tuner_.reset(); }
  /// The tuning in progress, if any.
  const tspgl::PlaybackTuner* tuner() const { return tuner_.get(); }
  /// What the running tuning is for.
  const TuneKey& running_for() const { return running_for_; }
  /// What the last finished (or cached) tuning was for.
  const TuneKey& tuned_for() const { return tuned_for_; }
  /// One frame's share (pace: playing, until_next_ms, step_frame as TuningPace::budget; the
  /// step period period_ms); the finished ladder when the tuning ends (written to the disk
  /// cache; a cache error goes to note). Throws tsp::Error from the tuner (the tuning is
  /// dropped).
  std::optional<std::vector<tspgl::TunedRung>> advance(bool playing, double until_next_ms,
                                                       bool step_frame, double period_ms,
                                                       double now_s, std::int64_t frame,
                                                       std::string& note);
  /// True while the tuning waits for room before the next step (the window may sleep).
  bool waiting() const { return tuner_ && pace_.waiting(); }
  /// The window drew a frame of frame_ms while the tuning ran (period_ms: the step period while
  /// playing, else 0): the longest, and those over 1.5 periods (late). Never throws.
  void frame_drawn(double frame_ms, double period_ms);
  /// What `stats` writes as tuning: running, pictures, seconds, frames, the longest frame, the
  /// frames before the first picture, whether it came from the disk cache and its file.
  nlohmann::json stats() const;

 private:
  std::unique_ptr<tspgl::PlaybackTuner> tuner_;
  MakeTuner make_;
  double pixel_share_ = 1;  ///< of the probe's pixels, this tuning
  int restarts_ = 0;        ///< times it started again with fewer pixels
  TuningPace pace_;
  TuneKey running_for_, tuned_for_;
  nlohmann::json disk_key_;
  std::string cache_file_;
  bool from_cache_ = false;
  double started_s_ = 0;
  std::int64_t started_frame_ = 0;
  std::int64_t frames_before_first_picture_ = -1;  ///< from the start to the first picture
  double seconds_ = -1;                            ///< how long the last tuning took
  int frames_while_tuning_ = 0;
  double longest_frame_ms_ = 0;
  int late_frames_ = 0;  ///< playing frames over 1.5 step periods while it ran
};

}  // namespace tspplayer
