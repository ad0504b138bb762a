#include "player/viewer_session.h"

#include "tsp/core/stopwatch.h"
#include "tsp/metric/compute_errors.h"

namespace tspplayer {

ViewerSession::ViewerSession(std::unique_ptr<tsp::TspFile> file, const tsp::TransferFunction& tf,
                             tsp::Metric metric)
    : file_(std::move(file)), tf_(tf), metric_(metric) {
  set_metric(metric);  // (the reference metric has no lazy evaluation: File > Open threw)
}

ViewerSession::~ViewerSession() {
  prefetcher_.reset();  // its thread reads into the renderer's brick cache
  driver_.reset();
  renderer_.reset();
}

int ViewerSession::steps() const {
  return file_->tree().time().steps();
}

void ViewerSession::set_metric(tsp::Metric m) {
  metric_ = m;
  if (m != tsp::Metric::reference)
    lazy_ = std::make_unique<tsp::LazyErrors>(file_->tree(), m, tf_);
  else
    reference_version_ = ~std::uint64_t(0);
}

void ViewerSession::tf_replaced() {
  if (lazy_) lazy_->set_transfer_function(tf_);
}

void ViewerSession::evaluate_step(int step) {
  if (metric_ == tsp::Metric::reference) return;
  // Evaluate this step's nodes here so the HUD can show the recompute cost; render() then
  // only reads memoised results.
  const std::int64_t before = lazy_->evaluations();
  const tsp::Stopwatch t0;
  lazy_->errors_for_step(step);
  const double ms = t0.ms();
  if (lazy_->evaluations() > before) {
    metric_ms_ = ms;
    metric_evaluations_ = lazy_->evaluations() - before;
  }
}

tsp::FrameMetric& ViewerSession::frame_metric() {
  if (metric_ != tsp::Metric::reference) return *lazy_;
  if (reference_version_ != tf_.version()) {
    // The reference metric reads every voxel: computed in full, blocking (the UI says so).
    const tsp::Stopwatch t0;
    reference_ = tsp::compute_errors(tsp::Metric::reference, file_->tree(), tf_, file_.get(), 0);
    metric_ms_ = t0.ms();
    metric_evaluations_ = std::int64_t(reference_.transparent.size());
    reference_version_ = tf_.version();
  }
  return reference_nodes_;
}

const tsp::NodeErrors& ViewerSession::errors_for_step(int step) {
  // (The reference metric of a file just opened or swapped in is computed here, not read stale.)
  return frame_metric().errors_for_step(step);
}

void ViewerSession::make_renderer(tspgl::GlContext& ctx, tsp::CachePolicy cache,
                                  std::int64_t texture_budget, std::int64_t ram_budget,
                                  std::shared_ptr<tspgl::SliceCompositor>& programs) {
  prefetcher_.reset();
  // The programs are compiled once per window and shared by every renderer made after.
  if (renderer_) programs = renderer_->compositor();
  driver_.reset();
  renderer_.reset();
  renderer_ = std::make_unique<tspgl::VolumeRenderer>(ctx, *file_, cache, texture_budget,
                                                      ram_budget, programs);
  renderer_->set_transfer_function(tf_);
  prefetcher_ = std::make_unique<tsp::BrickPrefetcher>(renderer_->brick_cache());
}

void ViewerSession::adopt_renderer(std::unique_ptr<tspgl::VolumeRenderer> r) {
  prefetcher_.reset();
  driver_.reset();
  renderer_ = std::move(r);
  renderer_->set_transfer_function(tf_);
  prefetcher_ = std::make_unique<tsp::BrickPrefetcher>(renderer_->brick_cache());
}

std::pair<std::unique_ptr<tsp::TspFile>, std::unique_ptr<tspgl::VolumeRenderer>>
ViewerSession::swap_field(std::unique_ptr<tsp::TspFile> next,
                          std::shared_ptr<tspgl::SliceCompositor>& programs) {
  prefetcher_.reset();  // it reads into the renderer's brick cache
  driver_.reset();
  if (renderer_) programs = renderer_->compositor();
  std::pair<std::unique_ptr<tsp::TspFile>, std::unique_ptr<tspgl::VolumeRenderer>> old{
      std::move(file_), std::move(renderer_)};
  file_ = std::move(next);
  lazy_.reset();  // (of the other field's tree)
  set_metric(metric_);
  reference_version_ = ~std::uint64_t(0);
  return old;
}

tspgl::FrameDriver& ViewerSession::driver() {
  if (!driver_) driver_ = std::make_unique<tspgl::FrameDriver>(*renderer_);
  return *driver_;
}

}  // namespace tspplayer
