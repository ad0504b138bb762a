#include "render/baseline_renderer.h"

#include <algorithm>
#include <cstring>

#include "render/brick_textures.h"
#include "tsp/core/stopwatch.h"
#include "tsp/frame/frame_plan.h"
#include "tsp/frame/slicer.h"

namespace tspgl {

BaselineRenderer::BaselineRenderer(GlContext& ctx, const tsp::BrickStore& bricks,
                                   std::int64_t brick_budget)
    : tree_(bricks.tree()), bricks_(bricks, brick_budget), compositor_(ctx) {
  compositor_.set_stencil(tree_.has_stencil());
}

BaselineRenderer::~BaselineRenderer() {
  if (texture_) compositor_.context().gl().DeleteTextures(1, &texture_);
}

void BaselineRenderer::set_transfer_function(const tsp::TransferFunction& tf) {
  compositor_.set_transfer_function(tf, tree_.value_range());
}

FrameReport BaselineRenderer::render(int step, const tsp::Camera& camera,
                                     const RenderSettings& settings) {
  const tsp::Stopwatch frame;
  const tsp::Octree& octree = tree_.octree();
  const tsp::Dims d = octree.dims();
  const GlApi& gl = compositor_.context().gl();
  FrameReport r;
  r.step = step;
  RenderSettings uniform = settings;
  uniform.sampling_tol = 0;  // the non-TSP baseline samples every spacing everywhere
  compositor_.begin_frame(camera, uniform);
  r.backend = compositor_.cpu_frame() ? "cpu" : "gl";
  r.backend_note = compositor_.backend_note();

  // The whole step, assembled from the bricks and uploaded as one texture, every frame.
  tsp::Stopwatch phase;
  // With a stencil the bricks carry their flags after the codes: the volume interleaves both.
  const int channels = tree_.has_stencil() ? 2 : 1;
  if (volume_.size != std::array<int, 3>{d.x, d.y, d.z} || volume_.channels != channels)
    volume_.allocate(d.x, d.y, d.z, channels);
  for (int b = 0; b < octree.brick_count(); ++b) {
    tsp::BrickSamples samples = bricks_.get(b, step);
    const tsp::Box s = octree.brick_samples(b);
    const std::size_t n = std::size_t(s.count());
    std::size_t i = 0;
    for (int z = s.lo[2]; z < s.hi[2]; ++z)
      for (int y = s.lo[1]; y < s.hi[1]; ++y, i += std::size_t(s.size(0))) {
        const std::size_t dst = s.lo[0] + std::size_t(d.x) * (y + std::size_t(d.y) * z);
        if (channels == 1) {
          std::memcpy(volume_.texels.data() + dst, samples->data() + i,
                      std::size_t(s.size(0)) * sizeof(std::uint16_t));
          continue;
        }
        for (int x = 0; x < s.size(0); ++x) {
          volume_.texels[2 * (dst + std::size_t(x))] = (*samples)[i + std::size_t(x)];
          volume_.texels[2 * (dst + std::size_t(x)) + 1] = (*samples)[n + i + std::size_t(x)] ? 65535 : 0;
        }
      }
  }
  if (texture_) gl.DeleteTextures(1, &texture_);
  texture_ = create_scalar_texture(gl, d.x, d.y, d.z, volume_.texels.data(), channels);
  r.upload_ms = phase.lap_ms();
  r.bytes_uploaded = d.count() * std::int64_t(sizeof(std::uint16_t));
  r.textures_resident = 1;
  r.texture_bytes = r.bytes_uploaded;

  soup_.clear();
  const tsp::Box all{{0, 0, 0}, {d.x, d.y, d.z}};
  const BrickSlot slot{texture_, {0.5f, 0.5f, 0.5f}, {d.x, d.y, d.z}, {1, 1, 1}, &volume_};
  if (settings.compositing == Compositing::rays) {
    // One "brick", the whole volume, for the same one-pass ray caster the TSP renderer uses.
    pages_.reset({1, 1, 1}, {std::max(d.x - 1, 1), std::max(d.y - 1, 1), std::max(d.z - 1, 1)});
    pages_.set_textured(0, slot);
    pages_.finish();
    r.slicing_ms = phase.lap_ms();
    compositor_.set_pages(pages_, d);
    compositor_.draw_rays();
    r.boxes = 1;
  } else {
    DrawItem item;
    item.bounds = tsp::geometric_box(all, d);
    item.slot = slot;
    item.as_box = settings.compositing == Compositing::boxes;
    if (!item.as_box) {
      const tsp::IncrementalSlicer slicer(
          tsp::SlicePlanes::toward(camera.direction(), settings.spacing * camera.ray_cosine()));
      slicer.slice(item.bounds, soup_);
      item.polygon_count = int(soup_.size());
      compositor_.upload(soup_);
    }
    r.slicing_ms = phase.lap_ms();
    r.polygons = std::int64_t(soup_.size());
    r.boxes = item.as_box;
    compositor_.draw({item});
  }
  r.fragments = compositor_.end_frame();
  r.samples = compositor_.cpu_samples();
  r.draw_ms = phase.lap_ms();
  r.ms = frame.ms();
  r.class_percent[std::size_t(tsp::DrawClass::new_texture)] = 100.0;
  return r;
}

}  // namespace tspgl
