// What opening a file creates in the player (issue 44 item 4): the open file (the shown field),
// the error metric the frames read over the player's TF, the renderer with the prefetcher that
// reads into its brick cache, and the frame driver that draws with it. File > Open replaces the
// whole object; a field switch swaps the file and renderer inside it (the shelf keeps the old
// ones). The metric needs no window, so tests drive it without one; the renderer needs a GL
// context (an offscreen one will do).
#pragma once
#include <cstdint>
#include <memory>
#include <utility>

#include "gl/context.h"
#include "render/frame_driver.h"
#include "render/volume_renderer.h"
#include "tsp/metric/frame_metric.h"
#include "tsp/metric/lazy_errors.h"
#include "tsp/metric/metric.h"
#include "tsp/metric/transfer_function.h"
#include "tsp/store/brick_prefetcher.h"
#include "tsp/store/tsp_file.h"

namespace tspplayer {

/// One open file's file, metric, renderer, prefetcher and frame driver. Use from the GL thread.
class ViewerSession {
 public:
  /// Takes file and evaluates metric over tf (held by reference: it must outlive this object;
  /// its edits are seen through its version). No renderer until make_renderer(). Never throws
  /// but bad_alloc.
  ViewerSession(std::unique_ptr<tsp::TspFile> file, const tsp::TransferFunction& tf,
                tsp::Metric metric);
  /// Stops the prefetcher before the renderer whose cache it fills goes (the GL context must be
  /// current).
  ~ViewerSession();
  ViewerSession(const ViewerSession&) = delete;
  ViewerSession& operator=(const ViewerSession&) = delete;

  /// The open file (the shown field).
  tsp::TspFile& file() const { return *file_; }
  /// Number of steps of the file.
  int steps() const;

  // ---- the metric ----
  /// The metric frames read.
  tsp::Metric metric() const { return metric_; }
  /// Switches to metric m (scalar, approximate or perceptual: a fresh lazy evaluation;
  /// reference: computed in full, blocking, at the next frame_metric()). Never throws but
  /// bad_alloc.
  void set_metric(tsp::Metric m);
  /// The TF object was replaced whole (not edited): the lazy metric evaluates every node anew
  /// on demand. Never throws.
  void tf_replaced();
  /// Evaluates the lazy metric's nodes of step now (the reference metric: nothing), timing it
  /// for metric_ms() when it evaluated any. Never throws but bad_alloc.
  void evaluate_step(int step);
  /// The metric as frames read it (the reference metric brought up to the TF's version first).
  tsp::FrameMetric& frame_metric();
  /// The per-node errors of step under the metric (the reference metric brought up to date
  /// first, as frame_metric()).
  const tsp::NodeErrors& errors_for_step(int step);
  /// Milliseconds of the last metric evaluation that evaluated any node (0: none yet).
  double metric_ms() const { return metric_ms_; }
  /// Node evaluations of that evaluation.
  std::int64_t metric_evaluations() const { return metric_evaluations_; }

  // ---- the renderer ----
  /// True once make_renderer() or adopt_renderer() gave it a renderer.
  bool has_renderer() const { return renderer_ != nullptr; }
  /// The renderer that draws the file (has_renderer() asserted).
  tspgl::VolumeRenderer& renderer() const { return *renderer_; }
  /// The prefetcher reading into renderer()'s brick cache (has_renderer() asserted).
  tsp::BrickPrefetcher& prefetcher() const { return *prefetcher_; }
  /// (Re)makes the renderer for a cache policy and budgets (bytes), drawing the TF, with a new
  /// prefetcher and driver. programs: the compiled programs every renderer of the window
  /// shares, taken from the old renderer and given to the new. Throws tspgl::GlError.
  void make_renderer(tspgl::GlContext& ctx, tsp::CachePolicy cache, std::int64_t texture_budget,
                     std::int64_t ram_budget, std::shared_ptr<tspgl::SliceCompositor>& programs);
  /// Draws with r (a parked field's renderer) and the TF, with a new prefetcher and driver.
  /// Never throws but bad_alloc.
  void adopt_renderer(std::unique_ptr<tspgl::VolumeRenderer> r);
  /// Shows next (another field of the file) without a renderer until one is made or adopted:
  /// returns the file and renderer shown so far (programs: as make_renderer()), and the metric
  /// evaluates next's tree anew. Never throws but bad_alloc.
  std::pair<std::unique_ptr<tsp::TspFile>, std::unique_ptr<tspgl::VolumeRenderer>> swap_field(
      std::unique_ptr<tsp::TspFile> next, std::shared_ptr<tspgl::SliceCompositor>& programs);
  /// The frame driver of the renderer (made on first use after a renderer change).
  tspgl::FrameDriver& driver();
  /// The next frame starts a new LOD controller (LOD turned off and on). Never throws.
  void reset_lod() {
    if (driver_) driver_->set_lod({});
  }

 private:
  std::unique_ptr<tsp::TspFile> file_;
  const tsp::TransferFunction& tf_;
  tsp::Metric metric_;
  std::unique_ptr<tsp::LazyErrors> lazy_;
  tsp::MetricResult reference_;
  tsp::WholeTreeMetric reference_nodes_{reference_};  ///< reference_ as a FrameMetric
  std::uint64_t reference_version_ = ~std::uint64_t(0);
  double metric_ms_ = 0;
  std::int64_t metric_evaluations_ = 0;
  std::unique_ptr<tspgl::VolumeRenderer> renderer_;
  std::unique_ptr<tsp::BrickPrefetcher> prefetcher_;  ///< fills renderer_'s cache; made after it
  std::unique_ptr<tspgl::FrameDriver> driver_;        ///< draws renderer_'s frames
};

}  // namespace tspplayer
