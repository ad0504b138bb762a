// Follows the VTKHDF file format specification, version 2.x (VTK documentation "VTKHDF File
// Format", sections "Image data" and "Temporal/Transient Data"; current 2.5):
//  - /VTKHDF has attributes Version = [major, minor], Type = "ImageData", WholeExtent (6 ints),
//    Origin, Spacing (recorded as the grid's geometry), Direction (ignored: axis-aligned).
//    Version 1.x files may lack Type; like VTK we then take WholeExtent to mean ImageData.
//  - /VTKHDF/PointData/<name> and /VTKHDF/CellData/<name> hold the arrays with dimensions
//    ordered (z, y, x[, components]); as in VTK's reader, z is dropped when WholeExtent is flat
//    in z, and y too when it is also flat in y.
//  - Transient files add /VTKHDF/Steps with attribute NSteps; the arrays gain a leading time
//    dimension (time, z, y, x) and Steps/PointDataOffsets/<name> (CellDataOffsets) gives, per
//    step, the index along that dimension to read (steps may share data); without an offsets
//    dataset step t reads index t, as VTK's vtkHDFReader does.
#include "tsp/source/vtkhdf_source.h"

#include <cassert>
#include <climits>
#include <cmath>
#include <cstdio>
#include <optional>
#include <vector>

#include "tsp/core/error.h"
#include "tsp/hdf5/hdf5_values.h"
#include "tsp/source/grid_geometry.h"

namespace tsp::io {
namespace {

using h5::Handle;

constexpr int kMaxMajorVersion = 2;
const char* const kRoot = "/VTKHDF";

std::string shape_text(const std::vector<hsize_t>& shape) {
  std::string s;
  for (std::size_t i = 0; i < shape.size(); ++i) s += (i ? "x" : "") + std::to_string(shape[i]);
  return s.empty() ? "scalar" : s;
}


std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + v[i];
  return v.empty() ? "none" : s;
}

// Reads a 1-D integer dataset (an offsets table) as int64 values.
std::vector<long long> read_index_table(hid_t file, const std::string& ds_path,
                                        const std::string& where) {
  Handle ds(H5Dopen2(file, ds_path.c_str(), H5P_DEFAULT));
  if (!ds) throw FormatError(where + ": " + ds_path + " cannot be opened");
  Handle type(H5Dget_type(ds.get()));
  if (H5Tget_class(type.get()) != H5T_INTEGER)
    throw FormatError(where + ": " + ds_path + " is " + describe_h5_type(type.get()) +
                      ", expected integers");
  std::vector<hsize_t> shape = h5::dataset_shape(ds.get());
  if (shape.size() != 1)
    throw FormatError(where + ": " + ds_path + " has shape " + shape_text(shape) +
                      ", expected one value per step");
  std::vector<long long> v(static_cast<std::size_t>(shape[0]));
  if (!v.empty() &&
      H5Dread(ds.get(), H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) < 0)
    throw FormatError(where + ": " + ds_path + " cannot be read");
  return v;
}

// The PointData group's "Scalars" attribute (the active scalars), if any.
std::optional<std::string> active_scalars(hid_t file, const std::string& where) {
  if (!h5::exists(file, "/VTKHDF/PointData")) return std::nullopt;
  Handle group(H5Gopen2(file, "/VTKHDF/PointData", H5P_DEFAULT));
  if (!group) return std::nullopt;
  return string_attribute(group.get(), "Scalars", where + "/PointData");
}

class VtkHdfSource final : public VolumeSource {
 public:
  VtkHdfSource(std::string path, Handle file, std::string array_path, Dims dims, VolumeSlab slab,
               bool transient, std::vector<hsize_t> time_index)
      : path_(std::move(path)),
        file_(std::move(file)),
        array_path_(std::move(array_path)),
        dims_(dims),
        slab_(std::move(slab)),
        transient_(transient),
        time_index_(std::move(time_index)) {}

  Dims dims() const override { return dims_; }
  std::array<double, 3> origin() const override { return geometry_.origin; }
  std::array<double, 3> spacing() const override { return geometry_.spacing; }
  GridGeometry geometry_;
  int steps() const override { return transient_ ? int(time_index_.size()) : 1; }
  std::string describe() const override { return path_ + ", VTKHDF ImageData " + array_path_; }
  std::string field() const override { return array_path_.substr(array_path_.rfind('/') + 1); }
  std::vector<std::string> files() const override { return {path_}; }

  void read_step(int t, std::span<float> out) override { read_slab(t, 0, dims_.z, out); }
  bool reads_slabs() const override { return true; }
  void read_slab(int t, int z0, int z1, std::span<float> out) override {
    assert(t >= 0 && t < steps() && 0 <= z0 && z0 < z1 && z1 <= dims_.z);
    assert(std::int64_t(out.size()) == std::int64_t(dims_.x) * dims_.y * (z1 - z0));
    const std::string where = path_ + ", dataset " + array_path_;
    Handle ds(H5Dopen2(file_.get(), array_path_.c_str(), H5P_DEFAULT));
    if (!ds) throw FormatError(where + ": dataset cannot be opened");
    VolumeSlab slab = slab_;
    if (transient_) slab.fixed = {time_index_[std::size_t(t)]};
    if (slab.spatial.size() == 3) {  // a flat image (fewer axes stored) has one plane
      slab.spatial[0] = hsize_t(z1 - z0);
      slab.offset = hsize_t(z0);
    }
    read_volume(
        ds.get(), slab, out,
        [](std::span<const double> in, std::span<float> o) {
          for (std::size_t i = 0; i < in.size(); ++i) o[i] = static_cast<float>(in[i]);
        },
        where);
  }

 private:
  std::string path_;
  Handle file_;
  std::string array_path_;
  Dims dims_;
  VolumeSlab slab_;
  bool transient_;
  std::vector<hsize_t> time_index_;
};

}  // namespace

bool is_vtkhdf(hid_t file) {
  if (!h5::exists(file, kRoot)) return false;
  Handle obj(H5Oopen(file, kRoot, H5P_DEFAULT));
  return obj && H5Iget_type(obj.get()) == H5I_GROUP;
}

namespace {

// The root group's Version (1.x or 2.x) and Type (ImageData; version 1 files may omit it).
void check_vtkhdf_header(hid_t root_group, hid_t file, const std::string& where) {
  auto version = numeric_attribute(root_group, "Version", where);
  if (!version || version->size() != 2)
    throw FormatError(where + ": attribute Version missing or not [major, minor]");
  if (!((*version)[0] >= 1 && (*version)[0] <= kMaxMajorVersion)) {
    // (%g: a crafted version is any double, which an int cannot hold)
    char text[64];
    std::snprintf(text, sizeof text, "%g.%g", (*version)[0], (*version)[1]);
    throw FormatError(where + ": VTKHDF version " + text + ", expected major version 1 or 2");
  }
  auto type = string_attribute(root_group, "Type", where);
  if (!type) {
    // Version 1.x files may omit Type; VTK deduces it from what the group holds.
    if (H5Aexists(root_group, "WholeExtent") > 0)
      type = "ImageData";
    else if (h5::exists(file, "/VTKHDF/NumberOfConnectivityIds"))
      type = "UnstructuredGrid";
    else
      throw FormatError(where + ": attribute Type missing, expected \"ImageData\"");
  }
  if (*type != "ImageData")
    throw FormatError(where + ": VTKHDF Type is \"" + *type +
                      "\", expected \"ImageData\" (only image data is a regular grid)");
}

using Extent = std::array<long long, 6>;

// WholeExtent: six integers, lo <= hi per axis.
Extent read_extent(hid_t root_group, const std::string& where) {
  auto extent_values = numeric_attribute(root_group, "WholeExtent", where);
  if (!extent_values || extent_values->size() != 6)
    throw FormatError(where + ": attribute WholeExtent missing or not 6 integers");
  Extent extent{};
  for (int i = 0; i < 6; ++i) {
    double v = (*extent_values)[std::size_t(i)];
    if (v != std::floor(v) || std::fabs(v) > INT_MAX)
      throw FormatError(where + ": WholeExtent holds " + std::to_string(v) + ", expected integers");
    extent[i] = static_cast<long long>(v);
  }
  for (int a = 0; a < 3; ++a)
    if (extent[2 * a + 1] < extent[2 * a] || extent[2 * a + 1] - extent[2 * a] >= INT_MAX)
      throw FormatError(where + ": WholeExtent axis " + std::to_string(a) + " is [" +
                        std::to_string(extent[2 * a]) + ", " + std::to_string(extent[2 * a + 1]) +
                        "], expected lo <= hi");

  return extent;
}

// The array to read: --field's, else the only point array, the only cell array, or the
// active scalars. Returns its name and whether it is cell data.
std::pair<std::string, bool> pick_array(hid_t file, const std::string& field,
                                        const std::string& where) {
  const std::vector<std::string> point_arrays = h5::datasets_in(file, "/VTKHDF/PointData");
  const std::vector<std::string> cell_arrays = h5::datasets_in(file, "/VTKHDF/CellData");
  auto contains = [](const std::vector<std::string>& v, const std::string& n) {
    for (const auto& s : v)
      if (s == n) return true;
    return false;
  };
  const std::string listing =
      "PointData: " + join(point_arrays) + "; CellData: " + join(cell_arrays);
  bool cells = false;
  std::string name = field;
  if (name.empty()) {
    if (point_arrays.size() == 1) {
      name = point_arrays[0];
    } else if (point_arrays.empty() && cell_arrays.size() == 1) {
      name = cell_arrays[0];
      cells = true;
    } else if (auto scalars = active_scalars(file, where);
               scalars && contains(point_arrays, *scalars)) {
      name = *scalars;
    } else {
      throw FormatError(where + ": no field given and no single array to default to (" + listing +
                        "); name one with --field");
    }
  } else if (contains(point_arrays, name)) {
  } else if (contains(cell_arrays, name)) {
    cells = true;
  } else {
    throw FormatError(where + ": field '" + name + "' not found; available arrays: " + listing);
  }
  return {name, cells};
}

// The time steps (group /VTKHDF/Steps): how many, and each one's index in the array's time
// axis (the offsets table, or 0, 1, 2, …).
struct StepTable {
  bool transient = false;
  int steps = 1;
  std::vector<long long> offsets;
};
StepTable read_step_table(hid_t file, const std::string& kind, const std::string& name,
                          const long long n[3], const std::string& path,
                          const std::string& where) {
  StepTable st;
  st.transient = h5::exists(file, "/VTKHDF/Steps");
  if (st.transient) {
    Handle steps(H5Gopen2(file, "/VTKHDF/Steps", H5P_DEFAULT));
    if (!steps) throw FormatError(where + ": Steps cannot be opened as a group");
    auto ns = numeric_attribute(steps.get(), "NSteps", where + "/Steps");
    if (!ns || ns->size() != 1 || (*ns)[0] < 1 || (*ns)[0] != std::floor((*ns)[0]) ||
        (*ns)[0] > INT_MAX)
      throw FormatError(where + "/Steps: attribute NSteps missing or not a positive integer");
    check_grid(n[0], n[1], n[2], std::int64_t((*ns)[0]), where + "/Steps, NSteps");
    st.steps = int((*ns)[0]);
    const std::string table = "/VTKHDF/Steps/" + kind + "Offsets/" + name;
    if (h5::exists(file, table)) {
      st.offsets = read_index_table(file, table, path);
      if (st.offsets.size() < std::size_t(st.steps))
        throw FormatError(path + ": " + table + " has " + std::to_string(st.offsets.size()) +
                          " entries, expected NSteps = " + std::to_string(st.steps));
      st.offsets.resize(std::size_t(st.steps));
    } else {
      for (int t = 0; t < st.steps; ++t) st.offsets.push_back(t);
    }
  }

  return st;
}

}  // namespace

std::unique_ptr<VolumeSource> open_vtkhdf_source(const std::string& path, h5::Handle file,
                                                 const SourceOptions& options) {
  const std::string where = path + ", group /VTKHDF";
  Handle root(H5Gopen2(file.get(), kRoot, H5P_DEFAULT));
  if (!root) throw FormatError(where + ": cannot be opened");

  check_vtkhdf_header(root.get(), file.get(), where);
  const Extent extent = read_extent(root.get(), where);
  const auto [name, cells] = pick_array(file.get(), options.field, where);
  const std::string kind = cells ? "CellData" : "PointData";
  const std::string array_path = std::string(kRoot) + "/" + kind + "/" + name;
  const std::string awhere = path + ", dataset " + array_path;

  // Grid size: points, or cells (an axis flat in the extent still counts one cell).
  long long n[3];
  for (int a = 0; a < 3; ++a) {
    long long len = extent[2 * a + 1] - extent[2 * a];
    n[a] = cells ? std::max(len, 1LL) : len + 1;
  }
  check_grid(n[0], n[1], n[2], 1, where + ", WholeExtent");
  const bool flat_z = extent[5] == extent[4], flat_y = extent[3] == extent[2];
  if (flat_y && !flat_z)
    throw FormatError(where + ": WholeExtent is flat in y but not in z, which VTKHDF cannot store");
  std::vector<hsize_t> spatial;  // outermost first, as stored
  if (!flat_z) spatial.push_back(hsize_t(n[2]));
  if (!flat_z || !flat_y) spatial.push_back(hsize_t(n[1]));
  spatial.push_back(hsize_t(n[0]));

  // Time steps.
  const StepTable st = read_step_table(file.get(), kind, name, n, path, where);
  const bool transient = st.transient;
  const int nsteps = st.steps;
  const std::vector<long long>& offsets = st.offsets;

  // Check the array's shape: [time,] spatial... [, components].
  Handle ds(H5Dopen2(file.get(), array_path.c_str(), H5P_DEFAULT));
  if (!ds) throw FormatError(awhere + ": dataset cannot be opened");
  require_numeric_dataset(ds.get(), awhere);
  std::vector<hsize_t> shape = h5::dataset_shape(ds.get());
  const std::size_t lead = transient ? 1 : 0;
  std::vector<hsize_t> expected;
  if (transient) expected.push_back(0);  // any number of stored steps
  expected.insert(expected.end(), spatial.begin(), spatial.end());
  bool match = shape.size() == expected.size() || shape.size() == expected.size() + 1;
  for (std::size_t i = lead; match && i < expected.size(); ++i) match = shape[i] == expected[i];
  if (!match) {
    std::string want = (transient ? "steps x " : "") + shape_text(spatial);
    throw FormatError(awhere + ": shape " + shape_text(shape) + ", expected " + want +
                      " (z, y, x from WholeExtent" + (cells ? ", cells" : "") +
                      ") with an optional components axis");
  }
  int trailing = 0;
  if (shape.size() == expected.size() + 1) {
    if (shape.back() != 1)
      throw FormatError(awhere + ": field " + name + " has " + std::to_string(shape.back()) +
                        " components; a scalar field is expected");
    trailing = 1;
  }
  std::vector<hsize_t> time_index;
  if (transient) {
    for (int t = 0; t < nsteps; ++t) {
      long long o = offsets[std::size_t(t)];
      if (o < 0 || hsize_t(o) >= shape[0])
        throw FormatError(awhere + ": step " + std::to_string(t) + " reads time index " +
                          std::to_string(o) + ", expected 0.." + std::to_string(shape[0]) +
                          " (exclusive)");
      time_index.push_back(hsize_t(o));
    }
  }
  VolumeSlab slab;
  slab.spatial = spatial;
  slab.trailing = trailing;
  const GridGeometry geometry =
      image_geometry(numeric_attribute(root.get(), "Origin", where),
                     numeric_attribute(root.get(), "Spacing", where), cells, where);
  auto source = std::make_unique<VtkHdfSource>(path, std::move(file), array_path,
                                               Dims{int(n[0]), int(n[1]), int(n[2])},
                                               std::move(slab), transient, std::move(time_index));
  source->geometry_ = geometry;
  return source;
}

}  // namespace tsp::io
