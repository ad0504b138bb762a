#include "tsp/voxelize/voxelized_source.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <optional>

#include "tsp/core/error.h"
#include "tsp/voxelize/mat3.h"

namespace tsp {
namespace {

double tet_volume(const TetMesh& m, const std::array<std::int64_t, 4>& t) {
  const double* p0 = m.points.data() + 3 * t[0];
  double e[3][3];
  for (int i = 0; i < 3; ++i)
    for (int a = 0; a < 3; ++a) e[i][a] = m.points[std::size_t(3 * t[std::size_t(i) + 1] + a)] - p0[a];
  return std::fabs(detail::det3(e)) / 6.0;
}

class VoxelizedSource final : public VolumeSource {
 public:
  VoxelizedSource(std::unique_ptr<MeshSource> source, VoxelGrid grid, VoxelizeOptions options,
                  Mesh first)
      : source_(std::move(source)), grid_(grid), options_(options), first_(std::move(first)) {}

  Dims dims() const override { return grid_.dims; }
  int steps() const override { return source_->steps(); }
  std::string describe() const override {
    return source_->describe() + ", voxelized to " + to_string(grid_.dims);
  }
  std::vector<std::string> files() const override { return source_->files(); }
  std::string field() const override { return source_->field(); }
  bool has_stencil() const override { return true; }
  std::vector<double> times() const override { return source_->times(); }
  std::array<double, 3> origin() const override { return grid_.origin; }
  std::array<double, 3> spacing() const override { return grid_.spacing; }

  void read_step(int t, std::span<float> out) override {
    std::vector<std::uint8_t> inside(out.size());
    read_step_inside(t, out, inside);
  }

  void read_step_inside(int t, std::span<float> out, std::span<std::uint8_t> inside) override {
    // Step 0 was read at open (for the grid rule): used once, not read again.
    Mesh mesh = t == 0 && first_ ? std::move(*first_) : source_->read_step(t);
    if (t == 0) first_.reset();
    if (mesh.cell_values && options_.cell_data == CellDataMode::points) {
      mesh.values = cell_values_to_points(mesh);
      mesh.cell_values = false;
    }
    VoxelizeStats stats;
    try {
      stats = voxelize(mesh, grid_, out, inside, options_.sample);
    } catch (const FormatError& e) {
      throw FormatError(source_->describe() + ", step " + std::to_string(t) + ": " + e.what());
    }
    if (stats.inside == 0)
      throw FormatError(source_->describe() + ", step " + std::to_string(t) + ": no voxel of the " +
                        to_string(grid_.dims) + " grid lies inside any of its " +
                        std::to_string(mesh.cell_count()) +
                        " cells (cells without volume, or smaller than a voxel: try a finer "
                        "--resolution)");
  }

 private:
  std::unique_ptr<MeshSource> source_;
  VoxelGrid grid_;
  VoxelizeOptions options_;
  std::optional<Mesh> first_;  // step 0 until the first read_step_inside(0)
};

}  // namespace

double median_cell_size(const TetMesh& m) {
  if (m.tets.empty()) return 0;
  std::vector<double> volume;
  for (std::size_t t = 0; t < m.tets.size(); ++t) {
    const std::size_t c = std::size_t(m.cell[t]);
    if (c >= volume.size()) volume.resize(c + 1, 0.0);
    volume[c] += tet_volume(m, m.tets[t]);
  }
  return median_cell_size(volume);
}

double median_cell_size(const std::vector<double>& volumes) {
  std::vector<double> size;
  for (double v : volumes)
    if (v > 0) size.push_back(std::cbrt(v));
  if (size.empty()) return 0;
  auto mid = size.begin() + std::ptrdiff_t(size.size() / 2);
  std::nth_element(size.begin(), mid, size.end());
  return *mid;
}

VoxelGrid choose_grid(const Aabb& b, double cell_size, const VoxelizeOptions& o,
                      std::int64_t max_samples) {
  if (o.resolution != 0 && o.voxel_size != 0)
    throw UsageError("--resolution and --voxel-size both given; choose one");
  if (o.resolution < 0 || (o.resolution > 0 && o.resolution < 2))
    throw UsageError("--resolution " + std::to_string(o.resolution) + ": expected 2 or more");
  if (o.voxel_size < 0 || !std::isfinite(o.voxel_size))
    throw UsageError("--voxel-size " + std::to_string(o.voxel_size) + ": expected a positive size");
  double longest = 0;
  for (int a = 0; a < 3; ++a) longest = std::max(longest, b.hi[a] - b.lo[a]);
  double h = 0;
  if (o.voxel_size > 0) {
    h = o.voxel_size;
  } else if (o.resolution > 0) {
    h = longest / (o.resolution - 1);
  } else {
    const double n =
        cell_size > 0 ? std::ceil(longest / cell_size - 1e-6) + 1 : kMaxDefaultResolution;
    const double samples = std::clamp(n, double(kMinDefaultResolution), double(kMaxDefaultResolution));
    h = longest / (samples - 1);
  }
  VoxelGrid g;
  std::int64_t total = 1;
  int n[3];
  for (int a = 0; a < 3; ++a) {
    const double cells = (b.hi[a] - b.lo[a]) / h;
    if (!(cells < double(max_samples)))
      throw UsageError("voxel size " + std::to_string(h) + " gives more than " +
                       std::to_string(max_samples) + " samples along an axis");
    n[a] = int(std::ceil(cells - 1e-9)) + 1;
    total *= n[a];
    if (total > max_samples)
      throw UsageError("voxel size " + std::to_string(h) + " gives a grid of more than " +
                       std::to_string(max_samples) +
                       " samples; choose a larger --voxel-size or a smaller --resolution");
    g.origin[a] = b.lo[a];
    g.spacing[a] = h;
  }
  g.dims = Dims{n[0], n[1], n[2]};
  return g;
}

std::unique_ptr<VolumeSource> voxelized_source(std::unique_ptr<MeshSource> source,
                                               const VoxelizeOptions& options) {
  Aabb all;
  double cell_size = 0;
  Mesh first;
  for (int t = 0; t < source->steps(); ++t) {
    Aabb b;
    if (t == 0) {  // the first step whole: its cells for the grid rule
      first = source->read_step(0);
      if (first.cell_count() == 0)
        throw FormatError(source->describe() + ": step 0 has no cells");
      if (options.resolution == 0 && options.voxel_size == 0)
        cell_size = median_cell_size(tetrahedralize(first));
      b = first.bounds();
    } else {
      b = source->bounds(t);
    }
    for (int a = 0; a < 3; ++a) {
      all.lo[a] = t ? std::min(all.lo[a], b.lo[a]) : b.lo[a];
      all.hi[a] = t ? std::max(all.hi[a], b.hi[a]) : b.hi[a];
    }
  }
  double longest = 0;
  for (int a = 0; a < 3; ++a) longest = std::max(longest, all.hi[a] - all.lo[a]);
  if (!(longest > 0))
    throw FormatError(source->describe() + ": the mesh has no extent (all points coincide)");
  for (int a = 0; a < 3; ++a)
    if (!(all.hi[a] - all.lo[a] > 0))
      throw FormatError(source->describe() + ": the mesh is flat (every point has " +
                        std::string(1, char('x' + a)) + " = " + std::to_string(all.lo[a]) +
                        "): a surface has no inside to voxelize, expected cells with volume");
  const VoxelGrid grid = choose_grid(all, cell_size, options);
  return std::make_unique<VoxelizedSource>(std::move(source), grid, options, std::move(first));
}

}  // namespace tsp
