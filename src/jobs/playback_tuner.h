// What the player plays with (docs/player.md, "Playing at a quality target"): a ladder of
// cheaper versions of the user's settings — larger slice spacing, a smaller render scale, a
// coarser LOD level everywhere — each probed on a few steps at the window's view size against
// the full-quality picture (the user's settings, no LOD cut), measuring its mean ΔE and frame
// time. Probed a piece at a time, so the window keeps drawing; the ΔE measured does not depend
// on the quality target or the speed, so moving either re-chooses at once (choose_rung), without
// probing again.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "gl/context.h"
#include "render/render_settings.h"
#include "tsp/frame/camera.h"
#include "tsp/metric/frame_metric.h"
#include "tsp/metric/transfer_function.h"
#include "tsp/report/image.h"
#include "tsp/store/brick_store.h"

namespace tspgl {

class ImageProbe;

/// One rung of the ladder: how it changes the user's settings.
struct Rung {
  const char* name = "full";    ///< how the HUD and stats name it
  double spacing_factor = 1;    ///< slice spacing × this
  double render_scale = 1;      ///< render scale (× the user's)
  int lod_level = 0;            ///< an LOD level drawn everywhere (0: full resolution)
};

/// The ladder, full quality first, then roughly by falling cost. Never throws.
const std::vector<Rung>& playback_rungs();

/// The rung played before the first tuning ends (spacing ×4, scale 0.35: mean ΔE 0.4 with a
/// filled map, 1.2 with a sparse one, on the turbulence; a sixteenth of full quality's cost, so
/// the window keeps its frame rate while the tuning's pictures share its frames).
inline constexpr std::size_t kProvisionalRung = 8;

/// The most pixels a tuning's probe pictures have: a larger view is probed at its aspect, scaled
/// down to this (ΔE and the cost ratios between rungs change little; the window's measured time
/// corrects the probe's), so a tuning at 1280×800 costs a quarter.
inline constexpr int kMaxTunePixels = 640 * 400;

/// The user's settings s as rung r draws them. Never throws.
RenderSettings rung_settings(const RenderSettings& s, const Rung& r);

/// What one rung measured: the mean over the probe steps of each picture's mean ΔE against the
/// full-quality picture, the largest per-step mean, and its median frame time (ms).
struct TunedRung {
  Rung rung;
  double mean_de = 0, max_step_de = 0, ms = 0;
};

/// Which rung to play, and whether it holds the rate and the quality.
struct RungChoice {
  int index = 0;          ///< into the tuned rungs
  bool fits_rate = true;  ///< predicted frame time within the step period
  bool within_quality = true;  ///< its worst probe step within the quality target
  double predicted_ms = 0;     ///< its frame time as the window would draw it
};

/// Share of the quality target a rung's mean ΔE over the probe steps may use (the steps played
/// differ from the probed ones). Measured on held-out screenshots at 1280×800 (docs/results.md,
/// issue 27) the probe's ΔE at ≤ 640×400 was 1.0–2.3× the shown frames' ΔE, so 0.9 leaves a
/// margin without refusing rungs that keep the target (0.8 refused one at 0.88 shown at 0.69).
inline constexpr double kPlaybackQualityMargin = 0.9;

/// The rung to play from tuned (non-empty, tuned[0] full quality): a rung fits when ms ×
/// time_ratio + overhead_ms ≤ period_ms, and is within quality when its mean_de ≤
/// kPlaybackQualityMargin · target_de (the target is a mean over the frames shown). Of the rungs that do both, the one with the least ΔE
/// (then the fastest); else keep_quality: the fastest within quality (steps shown late), or
/// keep rate: of the rungs that fit the least ΔE, else the fastest. Never throws.
RungChoice choose_rung(const std::vector<TunedRung>& tuned, double period_ms, double time_ratio,
                       double overhead_ms, double target_de, bool keep_quality);

/// Probes the ladder a piece at a time on an offscreen canvas of ctx (current; the caller's
/// window: its framebuffer is left alone). Use from ctx's thread.
class PlaybackTuner {
 public:
  /// Tunes settings (the user's: full quality) over bricks under tf (copied) and nodes (the
  /// caller's live metric, used between advance() calls by the caller too: one thread), at the
  /// view camera, on `steps` evenly spread probe steps. bricks, nodes and ctx must outlive it.
  /// Throws tsp::GlError, tsp::UsageError (size).
  PlaybackTuner(GlContext& ctx, const tsp::BrickStore& bricks, const tsp::TransferFunction& tf,
                tsp::FrameMetric& nodes, const tsp::CameraParams& camera,
                const RenderSettings& settings, int steps = 3);
  ~PlaybackTuner();
  PlaybackTuner(const PlaybackTuner&) = delete;
  PlaybackTuner& operator=(const PlaybackTuner&) = delete;

  /// Renders for about budget_ms (at least one picture; a further one only when its predicted
  /// time, next_picture_ms(), fits what is left); returns done(). Throws tsp::Error on brick
  /// reads, tsp::GlError.
  bool advance(double budget_ms);
  /// The next picture's predicted time (ms): the last picture of its rung, else the last rung's
  /// median; −1 before the first picture (unknown). Never throws.
  double next_picture_ms() const;
  /// True once every rung was probed.
  bool done() const { return rungs_done_ == playback_rungs().size(); }
  /// Pictures rendered so far and in all (for a progress display).
  int pictures_done() const { return pictures_done_; }
  /// See pictures_done().
  int pictures_total() const;
  /// The rungs probed so far (all of them once done()), in ladder order.
  const std::vector<TunedRung>& tuned() const { return tuned_; }

 private:
  std::unique_ptr<ImageProbe> probe_;
  tsp::FrameMetric& nodes_;
  RenderSettings settings_;
  std::vector<tsp::Image> reference_;
  std::vector<TunedRung> tuned_;
  std::size_t rungs_done_ = 0, step_ = 0;
  TunedRung current_;
  std::vector<double> current_ms_;
  double last_ms_ = -1;  ///< the last picture's time (−1: none yet)
  int pictures_done_ = 0;
};

}  // namespace tspgl
