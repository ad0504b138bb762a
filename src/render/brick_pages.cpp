#include "render/brick_pages.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "tsp/metric/level_tf.h"

namespace tspgl {

namespace {
// Largest opacity per voxel a flat box is given, so that ln(1 − α) stays finite.
constexpr float kMaxFlatAlpha = 1.f - 1e-6f;
}  // namespace

float log_transmittance(float alpha) { return std::log1p(-std::clamp(alpha, 0.f, kMaxFlatAlpha)); }

void BrickPages::reset(std::array<int, 3> grid, std::array<int, 3> cell) {
  grid_ = grid;
  cell_ = cell;
  const std::size_t n = std::size_t(grid[0]) * grid[1] * grid[2];
  texels_.assign(4 * n, 0.f);
  atlas_ = {};
  runs_ = false;
}

void BrickPages::set_flat(int b, const tsp::Rgba& c) {
  if (!(c.a >= kMinFlatAlpha)) return;
  float* f = &texels_[4 * std::size_t(b)];
  f[0] = c.r;
  f[1] = c.g;
  f[2] = c.b;
  f[3] = log_transmittance(c.a);
}

void BrickPages::set_textured(int b, const BrickSlot& slot, bool clipped, int tf_row) {
  assert(tf_row >= 0 && tf_row < tsp::kLevelTfRows);
  atlas_ = slot;
  float* w = &texels_[4 * std::size_t(b)];
  w[0] = slot.offset[0];
  w[1] = slot.offset[1];
  w[2] = slot.offset[2];
  // w = 1 + lx + 8·ly + 64·lz with l = log2 of the LOD factor per axis (volume_ray.frag).
  int code = 0;
  for (int a = 2; a >= 0; --a) {
    const int l = std::clamp(int(std::lround(-std::log2(double(slot.scale[a])))), 0,
                             kMaxPageLevel);
    code = code * (kMaxPageLevel + 1) + l;
  }
  // + kClipFlag: the clip surface may cross it (its samples are tested against the solid).
  // + row · kLevelRowUnit: a level brick's TF row (exact in a float: below 2^24).
  w[3] = 1.f + float(code + (clipped ? kClipFlag : 0) + tf_row * kLevelRowUnit);
}

void BrickPages::finish() {
  // Chebyshev distance to the nearest non-empty brick, capped, by separable passes: the L∞
  // distance is a min over axes of nested maxima, d(p) = min_z max(|Δz|, min_y max(|Δy|,
  // min_x |Δx|)), and the cap bounds each pass's window.
  constexpr int kCap = kMaxLeapRadius + 1;
  const int nx = grid_[0], ny = grid_[1], nz = grid_[2];
  const auto at = [&](int x, int y, int z) { return std::size_t(x) + nx * (y + std::size_t(ny) * z); };
  std::vector<int> d(std::size_t(nx) * ny * nz), e(d.size());
  for (std::size_t i = 0; i < d.size(); ++i) d[i] = texels_[4 * i + 3] != 0.f ? 0 : kCap;
  const std::array<int, 3> stride{1, nx, nx * ny};
  for (int a = 0; a < 3; ++a) {
    for (int z = 0; z < nz; ++z)
      for (int y = 0; y < ny; ++y)
        for (int x = 0; x < nx; ++x) {
          const int p = a == 0 ? x : a == 1 ? y : z, n = grid_[a];
          const std::size_t i = at(x, y, z);
          int best = d[i];
          for (int k = 1; k < best && k < kCap; ++k) {
            if (p - k >= 0) best = std::min(best, std::max(k, d[i - k * std::size_t(stride[a])]));
            if (p + k < n) best = std::min(best, std::max(k, d[i + k * std::size_t(stride[a])]));
          }
          e[i] = best;
        }
    d.swap(e);
  }
  for (std::size_t i = 0; i < d.size(); ++i)
    if (texels_[4 * i + 3] == 0.f) texels_[4 * i] = float(std::max(0, d[i] - 1));
}

}  // namespace tspgl
