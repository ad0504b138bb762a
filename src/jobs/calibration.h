// `tspplay render --quality DE`: the fastest configuration of the quality knobs whose pictures
// stay within a mean ΔE of the full-quality picture (the baseline sliced at 0.25 voxels), picked
// from a calibration — every compositing × spacing × a log sweep of tolerances, probed on a
// sample of steps — made once per tree, TF, metric and view and cached as JSON
// (docs/rendering.md, "Quality target").
#pragma once
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "gl/context.h"
#include "jobs/knob_search.h"
#include "tsp/frame/camera.h"
#include "tsp/metric/metric.h"
#include "tsp/metric/transfer_function.h"
#include "tsp/store/brick_store.h"

namespace tspgl {

/// One probed configuration: the mean over the calibration steps of each picture's mean ΔE, the
/// largest of those per-step means, and the probe's median frame time.
struct CalibrationPoint {
  Knobs knobs;
  double mean_de = 0, max_step_de = 0, ms = 0;
};

/// What a calibration was made for, and every configuration it probed.
struct Calibration {
  nlohmann::json key;                   ///< file identity, TF, metric, camera, steps
  std::vector<CalibrationPoint> points;
};

/// What to calibrate.
struct CalibrationRequest {
  std::string tsp_path;  ///< the .tsp file the bricks come from (its identity keys the cache)
  std::string field;     ///< which of its fields ("": the first)
  tsp::Metric metric = tsp::Metric::approximate;
  tsp::CameraParams camera;
  int steps = 6;                 ///< calibration steps, spread evenly over the file's steps
  int sweep = 11;                ///< positive tolerances per compositing × spacing (log-spaced)
  /// The knobs swept; tolerance rules equal and temporal (a temporal tolerance alone merges
  /// steps without drawing nodes flat: on the turbulence the fastest way to ΔE 1).
  KnobGrid grid{.compositings = {Compositing::slices, Compositing::boxes, Compositing::rays},
                .spacings = {0.5, 1, 1.5, 2, 3, 4, 6, 8},
                .tolerance_rules = {ToleranceRule::equal, ToleranceRule::temporal}};
  double reference_spacing = 0.25;
  std::string cache_dir;         ///< "" : default_calibration_dir(); "-": no cache
};

/// Largest quality target accepted by --quality (ΔE; beyond it pictures are unrecognisable).
inline constexpr double kMaxQualityDe = 50;
/// Share of the target a configuration's worst calibration step may use: steps the calibration
/// did not see differ from those it saw (about 15 % on the generated shock series).
inline constexpr double kQualityMargin = 0.75;
/// The sweep's smallest positive tolerance, relative to the largest node error.
inline constexpr double kSweepDecades = 5;

/// The cache directory: $TSPPLAY_CACHE_DIR, else $XDG_CACHE_HOME/tspplay, else
/// $HOME/.cache/tspplay, else "" (no cache). Never throws.
std::string default_calibration_dir();

/// Progress: a phase text, probes done, probes planned (an upper bound).
using CalibrationProgress = std::function<void(const std::string& phase, int done, int total)>;

class ImageProbe;

/// A calibration made a piece at a time, so a window can spread it over its frames and keep
/// drawing: each advance() renders for about a time budget (at least one frame: a reference
/// step, or one step of one configuration), on an offscreen canvas of ctx — the caller's
/// current context, whose own framebuffer is left alone. Reads the cache first; writes it,
/// atomically, when done. Use from ctx's thread.
class Calibrator {
 public:
  /// Starts the calibration for r over bricks (the already opened r.tsp_path) under tf (copied;
  /// bricks and ctx must outlive it); done() at once when the cache has it. Throws
  /// tsp::UsageError, tsp::GlError; a corrupt cache file is recomputed, never an error.
  Calibrator(GlContext& ctx, const CalibrationRequest& r, const tsp::BrickStore& bricks,
             const tsp::TransferFunction& tf);
  ~Calibrator();
  Calibrator(const Calibrator&) = delete;
  Calibrator& operator=(const Calibrator&) = delete;

  /// Renders for about budget_ms (at least one frame; the metric is computed in one go), calling
  /// progress after each configuration; returns done(). Throws tsp::IoError (cache folder),
  /// tsp::FormatError, tsp::GlError, tsp::Error on brick reads.
  bool advance(double budget_ms, const CalibrationProgress& progress = {});
  /// True once every configuration was probed (or the cache had them).
  bool done() const { return done_; }
  /// Configurations probed so far, and how many there are (an upper bound before the metric is
  /// known).
  int probes_done() const { return int(calibration_.points.size()); }
  /// See probes_done().
  int probes_total() const;
  /// The calibration (complete once done()).
  const Calibration& calibration() const { return calibration_; }
  /// The cache file ("" without a cache).
  const std::string& cache_file() const { return cache_file_; }

 private:
  GlContext& ctx_;
  CalibrationRequest request_;
  const tsp::BrickStore& bricks_;
  tsp::TransferFunction tf_;
  std::vector<int> steps_;
  Calibration calibration_;
  std::string cache_file_;
  bool done_ = false;
  std::unique_ptr<ImageProbe> probe_;
  std::vector<tsp::Image> reference_;
  std::unique_ptr<tsp::MetricResult> metric_;
  std::vector<Knobs> queue_;       // the configurations, in probing order
  std::size_t next_ = 0;           // the configuration being probed
  std::size_t step_ = 0;           // its next step
  CalibrationPoint current_;       // what its steps measured so far
  std::vector<double> current_ms_;
  void plan();    // the metric and the queue of configurations
  void finish();  // writes the cache
};

/// The calibration for r over bricks (the already opened r.tsp_path) under tf, made in one go
/// (Calibrator advanced without a budget). `cache_file` is set to the file used ("" without a
/// cache). Throws like Calibrator.
Calibration calibrate(GlContext& ctx, const CalibrationRequest& r, const tsp::BrickStore& bricks,
                      const tsp::TransferFunction& tf, std::string* cache_file = nullptr,
                      const CalibrationProgress& progress = {});

/// The fastest point whose every calibration step stayed within kQualityMargin·de, or none.
std::optional<CalibrationPoint> pick_configuration(const Calibration& c, double de);

/// The JSON form of c (what the cache holds), and back. from_json throws tsp::FormatError
/// naming `what` on a malformed document (missing or mistyped keys, a spacing or tolerance
/// render would refuse, a negative or non-finite dE or time).
nlohmann::json to_json(const Calibration& c);
/// See to_json.
Calibration calibration_from_json(const nlohmann::json& j, const std::string& what);

}  // namespace tspgl
