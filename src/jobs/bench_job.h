// `tspplay bench` as a library call: the paper's Table 3 (zero tolerance: baseline against the
// TSP renderer per metric, texture cache off and on), Table 4 (per target image error against
// the full-quality picture: the fastest non-TSP configuration and, per metric, the fastest TSP
// configuration over every quality knob, timed) and Table 5 (class shares) on any .tsp file.
// Writes table3.csv, table4.csv, table5.csv, report.json and SVG plots. See docs/bench.md.
#pragma once
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "gl/headless.h"
#include "jobs/knob_search.h"
#include "jobs/tolerance_search.h"
#include "tsp/frame/camera.h"
#include "tsp/metric/metric.h"

namespace tspgl {

/// Most head-to-head rounds a bench may time (each round renders every winner again).
inline constexpr int kMaxRounds = 100;

/// Everything `tspplay bench` takes.
struct BenchOptions {
  std::string tsp_path;                           ///< the .tsp file
  std::string field;                              ///< --field: one of its fields ("": the first)
  std::vector<std::string> tfs{"preset:sparse"};  ///< transfer functions (file or preset:NAME)
  std::string out_dir;                            ///< report/ (created)
  int first_step = 0, last_step = -1;             ///< inclusive; −1: the last step
  tsp::CameraParams camera;                       ///< size and view
  std::vector<tsp::Metric> metrics{tsp::Metric::scalar, tsp::Metric::approximate,
                                   tsp::Metric::perceptual, tsp::Metric::reference};
  std::vector<double> targets{1.0, 3.0};  ///< target mean ΔE per Table-4 row ("slight", "moderate")
  int search_steps = 8;  ///< at most this many evenly spread steps are rendered per search probe
  int search_iterations = 10;  ///< bisection steps on the log-tolerance scale
  int passes = 2;             ///< timed runs play the steps this many times; the last pass counts
  Knobs table3;               ///< Table 3's compositing and spacing (tol and baseline unused)
  /// The full-quality picture every Table-4 error is measured against: the baseline, sliced.
  double reference_spacing = 0.25;
  KnobGrid baseline_grid{{Compositing::slices, Compositing::boxes, Compositing::rays},
                         {0.25, 0.5, 0.75, 1, 1.5, 2, 3, 4, 6, 8}};  ///< non-TSP search
  KnobGrid tsp_grid{{Compositing::slices, Compositing::boxes, Compositing::rays},
                    {0.5, 1, 1.5, 2, 3, 4, 6, 8}};  ///< TSP search (tolerance per cell)
  int timed_candidates = 3;   ///< fastest probes per target and renderer timed for real
  int head_to_head_rounds = 3;  ///< rounds timing the reference and every winner in turn
  std::string sweep = "quick";  ///< --sweep the defaults came from (for the report)
  HeadlessGl gl = HeadlessGl::automatic;  ///< --gl: which GL draws (gl/headless.h)
  int gpu = -1;                           ///< --gpu: EGL device index (−1: by gl's rule)
};

/// Progress: a line of text describing the phase, runs done and runs total.
using BenchProgress = std::function<void(const std::string& phase, int done, int total)>;

/// Runs every table and writes the report files into options.out_dir; returns report.json's
/// content. Throws tsp::UsageError (bad options), tsp::IoError / tsp::FormatError (files),
/// tsp::GlError.
nlohmann::json run_bench(const BenchOptions& options, const BenchProgress& progress = {});

}  // namespace tspgl
