#include "render/image_reuse.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>

#include "tsp/core/geometry.h"

namespace tspgl {

namespace {

// Identity packing: kind in the top bits, the key below.
constexpr int kKindShift = 48;
constexpr std::int64_t kTextured = 1, kFlat = 2, kDeferredFlat = 3;

std::int64_t pack(std::int64_t kind, std::int64_t key) { return (kind << kKindShift) | key; }

// A texture's steps as one number below kKindShift: its first and last step (steps < 2^24 in
// any tree we can hold).
constexpr int kStepBits = 24;
std::int64_t steps_of(const tsp::TextureKey& k) {
  return std::int64_t(k.t0) | (std::int64_t(k.last_step()) << kStepBits);
}

// The colour's exact bits, folded into one number (equal colours, equal numbers).
std::int64_t colour_bits(const tsp::Rgba& c) {
  std::uint64_t h = 1469598103934665603ull;
  for (float v : {c.r, c.g, c.b, c.a}) {
    std::uint32_t u = 0;
    std::memcpy(&u, &v, sizeof u);
    h = (h ^ u) * 1099511628211ull;
  }
  return std::int64_t(h);
}

// Page tags are scaled past every stored brick index (leaves and levels: < 2·kMaxBricks) so that
// (brick, tag) stays one number.
constexpr std::int64_t kPageTagStride = 2 * tsp::kMaxBricks;

}  // namespace

BrickIdentities brick_identities(const tsp::TspTree& tree, const tsp::FramePlan& plan,
                                 const std::function<tsp::Rgba(int)>& colour_of,
                                 std::span<const std::int64_t> level_pages) {
  const tsp::Octree& octree = tree.octree();
  BrickIdentities id(std::size_t(octree.brick_count()), {0, 0});
  for (const tsp::PlannedNode& n : plan.nodes) {
    if (n.cls == tsp::DrawClass::not_rendered) continue;
    const int tsp_id = tree.id(n.node.octree_id, n.node.time_id);
    const std::int64_t node = tsp_id;
    if (n.cls == tsp::DrawClass::untextured) {
      const std::array<std::int64_t, 2> flat{pack(kFlat, node), colour_bits(colour_of(tsp_id))};
      octree.for_each_brick(n.node.octree_id, [&](int b) { id[std::size_t(b)] = flat; });
      continue;
    }
    for (int i = n.first_texture; i < n.first_texture + n.texture_count; ++i) {
      const tsp::PlannedTexture& pt = plan.textures[std::size_t(i)];
      // A level brick stands for every leaf brick below its node; the stored brick index tells
      // a level's picture from the leaves', and the page tag how each leaf's page draws it.
      const bool level = pt.key.level > 0 && !pt.deferred;
      octree.for_each_brick(octree.stored_brick_node(pt.key.brick), [&](int b) {
        const std::int64_t page =
            level && !level_pages.empty() ? level_pages[std::size_t(b)] : 0;
        id[std::size_t(b)] =
            pt.deferred ? std::array<std::int64_t, 2>{pack(kDeferredFlat, node),
                                                      colour_bits(colour_of(tsp_id))}
                        : std::array<std::int64_t, 2>{pack(kTextured, steps_of(pt.key)),
                                                      pt.key.brick + page * kPageTagStride};
      });
    }
  }
  return id;
}

std::vector<PixelRect> dirty_rects(const tsp::TspTree& tree, const tsp::Camera& camera,
                                   const BrickIdentities& before, const BrickIdentities& now) {
  const tsp::Octree& octree = tree.octree();
  assert(int(before.size()) == octree.brick_count() && int(now.size()) == octree.brick_count());
  const int w = camera.params().width, h = camera.params().height;
  const int tx = (w + kReuseTile - 1) / kReuseTile, ty = (h + kReuseTile - 1) / kReuseTile;
  std::vector<std::uint8_t> tiles(std::size_t(tx) * ty, 0);
  bool any = false;
  for (int b = 0; b < octree.brick_count(); ++b) {
    if (before[std::size_t(b)] == now[std::size_t(b)]) continue;
    const tsp::Aabb box = tsp::geometric_box(octree.brick_box(b), octree.dims());
    const auto [x0, y0, x1, y1] = tsp::screen_footprint(camera, box).rect;
    // One pixel of margin for rasterisation at the edges.
    const int i0 = std::clamp(int(std::floor(x0 - 1)) / kReuseTile, 0, tx - 1);
    const int i1 = std::clamp(int(std::floor(x1 + 1)) / kReuseTile, 0, tx - 1);
    const int j0 = std::clamp(int(std::floor(y0 - 1)) / kReuseTile, 0, ty - 1);
    const int j1 = std::clamp(int(std::floor(y1 + 1)) / kReuseTile, 0, ty - 1);
    if (x1 < -1 || y1 < -1 || x0 > w + 1 || y0 > h + 1) continue;  // off screen
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) tiles[std::size_t(i + tx * j)] = 1;
    any = true;
  }
  std::vector<PixelRect> rects;
  if (!any) return rects;
  // Row runs of dirty tiles, a run joined with the one below when it spans the same columns.
  for (int j = 0; j < ty; ++j)
    for (int i = 0; i < tx;) {
      if (!tiles[std::size_t(i + tx * j)]) {
        ++i;
        continue;
      }
      int e = i;
      while (e < tx && tiles[std::size_t(e + tx * j)]) ++e;
      PixelRect r{i * kReuseTile, j * kReuseTile, std::min(e * kReuseTile, w),
                  std::min((j + 1) * kReuseTile, h)};
      auto above = std::find_if(rects.begin(), rects.end(), [&](const PixelRect& q) {
        return q.x0 == r.x0 && q.x1 == r.x1 && q.y1 == r.y0;
      });
      if (above != rects.end())
        above->y1 = r.y1;
      else
        rects.push_back(r);
      i = e;
    }
  if (int(rects.size()) > kMaxDirtyRects) {
    PixelRect all = rects.front();
    for (const PixelRect& r : rects) {
      all.x0 = std::min(all.x0, r.x0);
      all.y0 = std::min(all.y0, r.y0);
      all.x1 = std::max(all.x1, r.x1);
      all.y1 = std::max(all.y1, r.y1);
    }
    rects = {all};
  }
  return rects;
}

}  // namespace tspgl
