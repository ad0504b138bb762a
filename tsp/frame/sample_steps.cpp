#include "tsp/frame/sample_steps.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <map>

namespace tsp {

namespace {
constexpr int kCodes = 65536;
constexpr double kMaxCode = 65535.0;

// Max filter of radius r along each axis in turn (a Chebyshev ball).
std::vector<float> dilate(const std::vector<float>& v, std::array<int, 3> n, int r) {
  std::vector<float> a = v, b(v.size());
  const std::array<std::size_t, 3> stride{1, std::size_t(n[0]), std::size_t(n[0]) * n[1]};
  for (int axis = 0; axis < 3; ++axis) {
    for (int z = 0; z < n[2]; ++z)
      for (int y = 0; y < n[1]; ++y)
        for (int x = 0; x < n[0]; ++x) {
          const int p[3] = {x, y, z};
          const std::size_t i = std::size_t(x) + std::size_t(y) * stride[1] + std::size_t(z) * stride[2];
          float m = 0;
          for (int k = std::max(0, p[axis] - r); k <= std::min(n[axis] - 1, p[axis] + r); ++k)
            m = std::max(m, a[i + (std::size_t(k) - std::size_t(p[axis])) * stride[std::size_t(axis)]]);
          b[i] = m;
        }
    a.swap(b);
  }
  return a;
}
}  // namespace

std::array<int, 3> step_grid(Dims dims) {
  return {(dims.x - 1) / kStepCell + 1, (dims.y - 1) / kStepCell + 1, (dims.z - 1) / kStepCell + 1};
}

SampleVariation::SampleVariation(const TransferFunction& tf, ValueRange quantized)
    : entry_(kCodes) {
  // The same map as the renderer's TF lookup: coordinate = code/65535 · scale + offset, entry
  // floor(coordinate · K) clamped (render/tf_texture.cpp).
  const ValueRange d = tf.domain();
  const double scale = quantized.width() / d.width(), offset = (quantized.lo - d.lo) / d.width();
  const int k = tf.size();
  for (int c = 0; c < kCodes; ++c) {
    const double coord = double(c) / kMaxCode * scale + offset;
    entry_[std::size_t(c)] = std::uint16_t(std::clamp(int(std::floor(coord * k)), 0, k - 1));
  }
  colour_.reserve(std::size_t(k));
  for (const Rgba& e : tf.entries()) colour_.push_back({e.r * e.a, e.g * e.a, e.b * e.a, e.a});
}

CellVariations SampleVariation::cells(const std::uint16_t* codes, const Box& box) const {
  CellVariations out;
  std::array<std::vector<int>, 3> cell_of;  // per sample along each axis: its local cell
  for (int a = 0; a < 3; ++a) {
    out.first[std::size_t(a)] = box.lo[std::size_t(a)] / kStepCell;
    out.count[std::size_t(a)] = (box.hi[std::size_t(a)] - 1) / kStepCell - out.first[std::size_t(a)] + 1;
    for (int p = box.lo[std::size_t(a)]; p < box.hi[std::size_t(a)]; ++p)
      cell_of[std::size_t(a)].push_back(p / kStepCell - out.first[std::size_t(a)]);
  }
  out.v.assign(std::size_t(out.count[0]) * out.count[1] * out.count[2], 0.f);
  const std::size_t nx = std::size_t(box.size(0)), ny = std::size_t(box.size(1)),
                    nz = std::size_t(box.size(2));
  auto diff = [&](std::uint16_t a, std::uint16_t b) {
    const std::uint16_t ea = entry_[a], eb = entry_[b];
    if (ea == eb) return 0.f;
    const auto& p = colour_[ea];
    const auto& q = colour_[eb];
    return std::max(std::max(std::abs(p[0] - q[0]), std::abs(p[1] - q[1])),
                    std::max(std::abs(p[2] - q[2]), std::abs(p[3] - q[3])));
  };
  for (std::size_t z = 0; z < nz; ++z)
    for (std::size_t y = 0; y < ny; ++y) {
      const std::uint16_t* row = codes + (z * ny + y) * nx;
      float* cells = out.v.data() + (std::size_t(cell_of[2][z]) * std::size_t(out.count[1]) +
                                     std::size_t(cell_of[1][y])) * std::size_t(out.count[0]);
      for (std::size_t x = 0; x < nx; ++x) {
        float v = 0.f;
        if (x + 1 < nx) v = diff(row[x], row[x + 1]);
        if (y + 1 < ny) v = std::max(v, diff(row[x], row[x + nx]));
        if (z + 1 < nz) v = std::max(v, diff(row[x], row[x + nx * ny]));
        float& c = cells[cell_of[0][x]];
        c = std::max(c, v);
      }
    }
  return out;
}

std::vector<std::uint8_t> step_rows(const std::vector<float>& variation, std::array<int, 3> grid,
                                    double spacing, double tol) {
  assert(spacing > 0);
  assert(variation.size() == std::size_t(grid[0]) * grid[1] * grid[2]);
  std::vector<std::uint8_t> rows(variation.size(), 0);
  if (!(tol > 0)) return rows;
  std::map<int, std::vector<float>> dilated;  // reach → the variation's max over that ball
  for (int r = int(kStepMultipliers.size()) - 1; r >= 1; --r) {
    const double step = spacing * kStepMultipliers[std::size_t(r)];
    const int reach = int(std::ceil(step / kStepCell));
    auto it = dilated.find(reach);
    if (it == dilated.end()) it = dilated.emplace(reach, dilate(variation, grid, reach)).first;
    for (std::size_t i = 0; i < rows.size(); ++i)
      if (rows[i] == 0 && double(it->second[i]) * step <= tol) rows[i] = std::uint8_t(r);
  }
  return rows;
}

}  // namespace tsp
