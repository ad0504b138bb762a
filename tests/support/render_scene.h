// The render tests' scene (tests/render/*_test.cpp): a .tsp built from a source, opened with an
// offscreen context (OSMesa), its TSP and baseline renderers and its metric, and image checks
// that keep the pictures of a failed comparison.
#pragma once
#include <memory>
#include <optional>
#include <string>

#include "gl/context.h"
#include "render/baseline_renderer.h"
#include "render/volume_renderer.h"
#include "tsp/metric/compute_errors.h"
#include "tsp/report/image.h"
#include "tsp/source/volume_source.h"
#include "tsp/store/tsp_file.h"

namespace tsptest {

/// Builds src into a fresh temporary NAME.tsp (bricks of `brick`, the value range given or the
/// data's) and returns its path.
std::string build_tsp(tsp::VolumeSource& src, const std::string& name,
                      std::optional<tsp::ValueRange> range = {}, int brick = 16);

/// Writes actual, expected and difference PNGs to test-output/NAME and returns the folder.
std::string keep_failure(const std::string& name, const tsp::Image& actual,
                         const tsp::Image& expected);

/// Expects mean and p99 ΔE of actual against expected below the limits; on failure the message
/// names the folder keep_failure wrote.
void expect_close(const std::string& name, const tsp::Image& actual, const tsp::Image& expected,
                  double max_mean, double max_p99);

/// A TF of one colour and opacity over [0, 1].
tsp::TransferFunction flat_tf(tsp::Rgba c);

/// A .tsp opened with an offscreen context, its TSP and baseline renderers on one TF, and the
/// metric the TSP renderer reads.
struct RenderScene {
  std::unique_ptr<tsp::TspFile> file;
  std::unique_ptr<tspgl::GlContext> ctx;
  std::unique_ptr<tspgl::VolumeRenderer> renderer;
  std::unique_ptr<tspgl::BaselineRenderer> baseline;
  tsp::TransferFunction tf;
  tsp::MetricResult metric;
  tsp::WholeTreeMetric nodes{metric};  ///< metric as the renderer reads it
  bool shade = true;                   ///< frames lit (the default) or unlit

  /// Opens path at w × h with TF t, the brick cache policy and metric m. Throws what opening
  /// the file or the context throws.
  RenderScene(const std::string& path, const tsp::TransferFunction& t, tsp::CachePolicy cache,
              int w = 160, int h = 120, tsp::Metric m = tsp::Metric::reference);
  /// An orthographic (or perspective) camera at azimuth and elevation, the target's size.
  tsp::Camera camera(double az = 30, double el = 20, bool perspective = false) const;
  /// The TSP renderer's frame of `step` at tolerances tol (lit per `shade`).
  tsp::Image tsp_frame(int step, const tsp::Camera& cam, tsp::Tolerances tol = {});
  /// The TSP renderer's frame of `step` with settings s.
  tsp::Image frame(int step, const tsp::Camera& cam, const tspgl::RenderSettings& s);
  /// The baseline renderer's frame of `step` (lit per `shade`).
  tsp::Image baseline_frame(int step, const tsp::Camera& cam);
};

}  // namespace tsptest
