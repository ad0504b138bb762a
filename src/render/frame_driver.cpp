#include "render/frame_driver.h"

#include <algorithm>
#include <cassert>

namespace tspgl {

FrameDriver::FrameDriver(VolumeRenderer& renderer, const LodSpec& lod) : renderer_(&renderer) {
  set_lod(lod);
}

FrameDriver::FrameDriver(BaselineRenderer& baseline) : baseline_(&baseline) {}

void FrameDriver::set_lod(const LodSpec& lod) {
  assert(renderer_ || lod.mode == LodMode::off);
  const bool keep_controller = controller_ && lod.mode == LodMode::adaptive;
  lod_ = lod;
  fixed_cut_.reset();
  filter_cut_.reset();
  if (lod.mode == LodMode::fixed) {
    const tsp::Octree& o = renderer_->tree().octree();
    fixed_cut_ = tsp::LodCut::at_level(o, std::clamp(lod.level, 0, o.max_lod_level()));
  }
  if (keep_controller)
    controller_->set_options(lod.options);
  else if (lod.mode == LodMode::adaptive)
    controller_ = std::make_unique<tsp::LodController>(renderer_->tree(), lod.options);
  else
    controller_.reset();
}

tsp::LodStops FrameDriver::current_stops() const {
  if (fixed_cut_) return fixed_cut_->stops();
  if (controller_) return controller_->stops();
  if (lod_.mode == LodMode::splat) return splats_.stops;
  if (filter_cut_) return filter_cut_->stops();
  return {};
}

tsp::LodFrameStats FrameDriver::update_cut(const FrameRequest& r) {
  assert(r.tf && r.camera && controller_);
  tsp::LodFrameStats st = controller_->update(*r.camera, r.step, *r.tf, r.settings.spacing,
                                              renderer_->clip_sides());
  if (lod_.converge) {  // untimed: refine until a round splits nothing
    int splits = st.splits;
    while (st.splits > 0) {
      st = controller_->update(*r.camera, r.step, *r.tf, r.settings.spacing,
                               renderer_->clip_sides());
      splits += st.splits;
    }
    st.splits = splits;
  }
  return st;
}

void FrameDriver::advance(const FrameRequest& r) {
  if (renderer_ && controller_ && lod_.mode == LodMode::adaptive && lod_.converge) update_cut(r);
}

DrawnFrame FrameDriver::draw(const FrameRequest& r) {
  assert(r.camera);
  DrawnFrame out;
  out.settings = r.settings;
  if (baseline_) {
    out.report = baseline_->render(r.step, *r.camera, out.settings);
    return out;
  }
  assert(r.metric);
  tsp::LodStops stops;
  switch (lod_.mode) {
    case LodMode::off:
      break;
    case LodMode::fixed:
      stops = fixed_cut_->stops();
      out.lod = tsp::cut_stats(*fixed_cut_);
      break;
    case LodMode::splat: {
      splats_ = tsp::splat_cut(renderer_->tree().octree(), *r.camera, lod_.splat_px,
                               renderer_->clip_sides());
      stops = splats_.stops;
      tsp::LodFrameStats st;
      st.cut_size = st.splats = splats_.size;
      st.splat_px = lod_.splat_px;
      out.lod = st;
      // Splats are flat boxes: composited one box each (the cheapest way to draw them measured,
      // docs/results.md); a clipped frame stays ray cast.
      out.settings.compositing = Compositing::boxes;
      break;
    }
    case LodMode::filter:  // LaMar's depth-first selection from this frame's camera
      filter_cut_ = tsp::selection_cut(renderer_->tree().octree(), *r.camera, lod_.filter);
      stops = filter_cut_->stops();
      out.lod = tsp::cut_stats(*filter_cut_);
      break;
    case LodMode::adaptive: {
      const tsp::LodFrameStats st = update_cut(r);
      stops = controller_->stops();
      if (controller_->splatting()) out.settings.compositing = Compositing::boxes;
      out.settings.render_scale = controller_->render_scale();
      out.lod = st;
      break;
    }
  }
  out.report = renderer_->render(r.step, *r.camera, out.settings, *r.metric, stops, r.part);
  if (controller_) controller_->measured(out.report.ms - out.report.upload_ms);
  return out;
}

}  // namespace tspgl
