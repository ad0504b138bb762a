// One frame driver: a FrameRequest (step, camera, settings, metric) turned into a frame by the
// TSP renderer or the baseline — the frame's LOD cut chosen (full resolution, one level
// everywhere, the adaptive controller's cut, the splat cut or a selection filter's cut), the settings the cut asks for
// applied (splats composited as boxes, the controller's render scale), the frame drawn and the
// controller fed its measured time. `render`, the player and the bench's and calibration's
// probes all draw through it, so what the bench measures is what the window plays.
#pragma once
#include <memory>
#include <optional>

#include "render/baseline_renderer.h"
#include "render/volume_renderer.h"
#include "tsp/frame/camera.h"
#include "tsp/lod/lod_controller.h"
#include "tsp/lod/lod_cut.h"
#include "tsp/lod/selection_filter.h"
#include "tsp/lod/splat_cut.h"
#include "tsp/metric/frame_metric.h"
#include "tsp/metric/transfer_function.h"

namespace tspgl {

/// How a frame's spatial LOD cut is chosen (render --lod off|K|auto|splat:PX, --lod-filter
/// distance|fov; the player's LOD).
enum class LodMode { off, fixed, adaptive, splat, filter };

/// The LOD cut frames are drawn with.
struct LodSpec {
  LodMode mode = LodMode::off;
  int level = 0;          ///< fixed: the level drawn everywhere (clamped to the tree's levels)
  double splat_px = 0;    ///< splat: the minimum splat size in pixels
  tsp::SelectionFilter filter;  ///< filter: LaMar's selection filter (distance or fov) and K
  tsp::LodOptions options;  ///< adaptive: the controller's options (target, limits, focus, ...)
  /// adaptive: each frame refines until nothing is left to split (an untimed, converged cut:
  /// render without --target-ms) instead of one update per frame (timed).
  bool converge = false;
};

/// One frame to draw.
struct FrameRequest {
  int step = 0;
  const tsp::Camera* camera = nullptr;     ///< the view (must be set)
  RenderSettings settings;                 ///< what it is drawn with
  tsp::FrameMetric* metric = nullptr;      ///< TSP renderer: the node errors (must be set)
  const tsp::TransferFunction* tf = nullptr;  ///< adaptive LOD: the TF the errors weigh
  /// TSP renderer: draw only these rectangles of the picture (progressive refinement).
  const PartialFrame* part = nullptr;
};

/// What a frame drew: the renderer's report and, with an LOD cut, what the cut did.
struct DrawnFrame {
  FrameReport report;
  std::optional<tsp::LodFrameStats> lod;  ///< none without an LOD cut
  RenderSettings settings;  ///< what it was drawn with (the request's, as the cut adjusted them)
};

/// Draws frames of one renderer under one LOD spec. Use from the renderer's GL thread.
class FrameDriver {
 public:
  /// Frames of the TSP renderer (which must outlive the driver) under lod. Never throws.
  FrameDriver(VolumeRenderer& renderer, const LodSpec& lod = {});
  /// Frames of the non-TSP baseline (no LOD; which must outlive the driver). Never throws.
  explicit FrameDriver(BaselineRenderer& baseline);

  /// Draws r. Throws what the renderers throw (tsp::Error on brick reads, tsp::GlError).
  DrawnFrame draw(const FrameRequest& r);
  /// Moves the cut on as draw(r) would, without drawing: an untimed adaptive cut (converge)
  /// depends on every frame before, so a split render's part (tspplay-mpi render) replays the
  /// frames it skips to draw its own with the whole render's cuts. The other modes keep nothing
  /// between frames that changes a picture (a timed cut follows measured times: not
  /// reproducible), so nothing is done. Never throws.
  void advance(const FrameRequest& r);
  /// Replaces the LOD spec: the adaptive controller is kept when the mode stays adaptive (its
  /// cut and cost model; the new options apply from the next frame), else made anew. Never
  /// throws.
  void set_lod(const LodSpec& lod);
  /// The LOD spec in use.
  const LodSpec& lod() const { return lod_; }
  /// The adaptive controller (null unless the mode is adaptive), e.g. for prefetching the
  /// bricks its next splits want.
  const tsp::LodController* controller() const { return controller_.get(); }
  /// The cut the next frame of r would draw without adapting it (for prefetch and readiness
  /// queries): the fixed cut's, the controller's current cut, or none. Never throws.
  tsp::LodStops current_stops() const;

 private:
  VolumeRenderer* renderer_ = nullptr;
  BaselineRenderer* baseline_ = nullptr;
  LodSpec lod_;
  std::optional<tsp::LodCut> fixed_cut_;
  std::optional<tsp::LodCut> filter_cut_;  // the filter's cut of the last frame
  std::unique_ptr<tsp::LodController> controller_;
  tsp::SplatCut splats_;

  // The adaptive controller's update(s) for r (converged when untimed).
  tsp::LodFrameStats update_cut(const FrameRequest& r);
};

}  // namespace tspgl
