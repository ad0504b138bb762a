#include "tsp/source/wrf_heights.h"

#include <algorithm>
#include <memory>
#include <mutex>
#include <vector>

#include "tsp/core/error.h"
#include "tsp/hdf5/hdf5_handle.h"
#include "tsp/hdf5/hdf5_lock.h"
#include "tsp/hdf5/hdf5_values.h"

namespace tsp::io {
namespace {

using h5::Handle;

// The 4-D shape of dataset `name` when it is a standard numeric dataset; empty otherwise.
std::vector<hsize_t> numeric_4d_shape(hid_t file, const char* name) {
  if (H5Lexists(file, name, H5P_DEFAULT) <= 0) return {};
  Handle ds(H5Dopen2(file, name, H5P_DEFAULT));
  if (!ds) return {};
  Handle type(H5Dget_type(ds.get()));
  if (!type || !is_standard_numeric_type(type.get())) return {};
  std::vector<hsize_t> shape = h5::dataset_shape(ds.get());
  return shape.size() == 4 ? shape : std::vector<hsize_t>{};
}

struct Geopotential {
  std::shared_ptr<Handle> file;
  std::vector<hsize_t> shape;  // (Time, bottom_top_stag, south_north, west_east)
  Dims dims;                   // the field's grid
  std::string where;
};

// (PH + PHB)[t] / g on the staggered levels and PH's plane, level-major, x fastest.
std::vector<double> staggered_heights(const Geopotential& g, int t) {
  const hsize_t count[4] = {1, g.shape[1], g.shape[2], g.shape[3]};
  const hsize_t start[4] = {hsize_t(t), 0, 0, 0};
  const hsize_t n = g.shape[1] * g.shape[2] * g.shape[3];
  std::vector<double> sum(static_cast<std::size_t>(n), 0.0), part(static_cast<std::size_t>(n));
  std::lock_guard lock(hdf5_mutex());
  for (const char* name : {"PH", "PHB"}) {
    Handle ds(H5Dopen2(g.file->get(), name, H5P_DEFAULT));
    Handle space(ds ? H5Dget_space(ds.get()) : H5I_INVALID_HID);
    Handle mem(H5Screate_simple(1, &n, nullptr));
    if (!ds || !space || !mem ||
        H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, start, nullptr, count, nullptr) < 0 ||
        H5Dread(ds.get(), H5T_NATIVE_DOUBLE, mem.get(), space.get(), H5P_DEFAULT, part.data()) < 0)
      throw FormatError(g.where + ": the geopotential " + name + " of step " + std::to_string(t) +
                        " cannot be read");
    for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += part[i];
  }
  for (double& v : sum) v /= kWrfGravity;
  return sum;
}

void field_heights(const Geopotential& g, int t, std::span<double> out) {
  const std::vector<double> s = staggered_heights(g, t);
  const int nx0 = int(g.shape[3]), ny0 = int(g.shape[2]), stag = int(g.shape[1]);
  const Dims d = g.dims;
  const bool mass = d.z == stag - 1, wide_x = d.x == nx0 + 1, wide_y = d.y == ny0 + 1;
  const auto at = [&](int k, int y, int x) {
    return s[(std::size_t(k) * std::size_t(ny0) + std::size_t(y)) * std::size_t(nx0) + std::size_t(x)];
  };
  // A column's height at staggered level k: the mean over the PH columns beside it.
  const auto column = [&](int k, int y, int x) {
    const int x0 = wide_x ? std::max(x - 1, 0) : x, x1 = wide_x ? std::min(x, nx0 - 1) : x;
    const int y0 = wide_y ? std::max(y - 1, 0) : y, y1 = wide_y ? std::min(y, ny0 - 1) : y;
    return 0.25 * (at(k, y0, x0) + at(k, y0, x1) + at(k, y1, x0) + at(k, y1, x1));
  };
  std::size_t i = 0;
  for (int k = 0; k < d.z; ++k)
    for (int y = 0; y < d.y; ++y)
      for (int x = 0; x < d.x; ++x, ++i)
        out[i] = mass ? 0.5 * (column(k, y, x) + column(k + 1, y, x)) : column(k, y, x);
}

}  // namespace

std::optional<LevelHeightsFn> wrf_level_heights(hid_t file, Dims dims, int steps,
                                                const std::string& where) {
  const std::vector<hsize_t> shape = numeric_4d_shape(file, "PH");
  if (shape.empty() || numeric_4d_shape(file, "PHB") != shape) return std::nullopt;
  if (shape[0] != hsize_t(steps) || shape[1] < 3 || shape[2] < 1 || shape[3] < 1) return std::nullopt;
  if (hsize_t(dims.z) != shape[1] && hsize_t(dims.z) != shape[1] - 1) return std::nullopt;
  if (hsize_t(dims.y) != shape[2] && hsize_t(dims.y) != shape[2] + 1) return std::nullopt;
  if (hsize_t(dims.x) != shape[3] && hsize_t(dims.x) != shape[3] + 1) return std::nullopt;
  auto own = std::make_shared<Handle>(H5Freopen(file));
  if (!*own) return std::nullopt;
  Geopotential g{std::move(own), shape, dims, where};
  return LevelHeightsFn([g = std::move(g)](int t, std::span<double> out) {
    field_heights(g, t, out);
  });
}

}  // namespace tsp::io
