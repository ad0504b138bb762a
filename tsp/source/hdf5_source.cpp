#include "tsp/source/hdf5_source.h"

#include <cassert>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <limits>
#include <optional>

#include "tsp/core/error.h"
#include "tsp/hdf5/hdf5_handle.h"
#include "tsp/hdf5/hdf5_values.h"
#include "tsp/source/grid_geometry.h"
#include "tsp/source/level_resample.h"
#include "tsp/source/natural_order.h"
#include "tsp/source/vtkhdf_source.h"
#include "tsp/source/wrf_heights.h"

namespace tsp::io {
namespace {

constexpr ssize_t kMaxNameChars = 4096;  // an object path longer than this is not a scale's

using h5::Handle;

std::string shape_text(const std::vector<hsize_t>& shape) {
  if (shape.empty()) return "scalar";
  std::string s;
  for (std::size_t i = 0; i < shape.size(); ++i) s += (i ? "x" : "") + std::to_string(shape[i]);
  return s;
}

// Every dataset of rank 3 or 4 in the file, as "/path (shape)", for messages and the default.
struct Candidate {
  std::string path;
  std::vector<hsize_t> shape;
  bool map_over_time = false;  // 3-D with time first: a 2-D field over time, not playable
};

bool is_map_over_time(hid_t ds, const std::vector<hsize_t>& shape);

herr_t collect_candidate(hid_t group, const char* name, const H5L_info_t*, void* data) {
  auto* out = static_cast<std::vector<Candidate>*>(data);
  // Soft or external links that dangle are skipped: only reachable datasets are candidates.
  if (H5Oexists_by_name(group, name, H5P_DEFAULT) <= 0) return 0;
  Handle obj(H5Oopen(group, name, H5P_DEFAULT));
  if (!obj || H5Iget_type(obj.get()) != H5I_DATASET) return 0;
  std::vector<hsize_t> shape = h5::dataset_shape(obj.get());
  if (shape.size() == 3 || shape.size() == 4)
    out->push_back({"/" + std::string(name), shape, is_map_over_time(obj.get(), shape)});
  return 0;
}

std::vector<Candidate> list_candidates(hid_t file) {
  std::vector<Candidate> found;
  H5Lvisit(file, H5_INDEX_NAME, H5_ITER_INC, collect_candidate, &found);
  return found;
}

// c without the 2-D fields over time.
std::vector<Candidate> playable(std::vector<Candidate> c) {
  std::erase_if(c, [](const Candidate& x) { return x.map_over_time; });
  return c;
}

std::string candidates_text(const std::vector<Candidate>& c) {
  if (c.empty()) return "none (no 3-D or 4-D dataset in the file)";
  std::string s;
  for (std::size_t i = 0; i < c.size(); ++i)
    s += (i ? ", " : "") + c[i].path + " (" + shape_text(c[i].shape) +
         (c[i].map_over_time ? ", 2-D over time: not playable" : "") + ")";
  return s;
}

// Converts (Z,Y,X) extents to Dims, refusing empty or oversized grids.
Dims dims_from_zyx(const hsize_t* zyx, std::int64_t steps, const std::string& where) {
  auto edge = [](hsize_t v) { return std::int64_t(std::min<hsize_t>(v, hsize_t(INT64_MAX))); };
  check_grid(edge(zyx[2]), edge(zyx[1]), edge(zyx[0]), steps, where);
  return Dims{int(zyx[2]), int(zyx[1]), int(zyx[0])};
}

// NetCDF (CF) packing of one variable: fill/missing samples → NaN, then v·scale + offset.
struct Packing {
  std::vector<double> missing;
  double scale = 1.0;
  double offset = 0.0;

  static Packing of(hid_t dataset, const std::string& where) {
    Packing p;
    for (const char* name : {"_FillValue", "missing_value"})
      if (auto v = numeric_attribute(dataset, name, where))
        p.missing.insert(p.missing.end(), v->begin(), v->end());
    auto single = [&](const char* name, double& dst) {
      if (auto v = numeric_attribute(dataset, name, where)) {
        if (v->size() != 1)
          throw FormatError(where + ": attribute " + name + " has " + std::to_string(v->size()) +
                            " values, expected 1");
        dst = (*v)[0];
        if (!std::isfinite(dst))
          throw FormatError(where + ": attribute " + name + " is " + std::to_string(dst) +
                            ", expected a finite number");
      }
    };
    single("scale_factor", p.scale);
    single("add_offset", p.offset);
    return p;
  }

  /// True when no sample is changed: values can be read straight into floats.
  bool identity() const { return missing.empty() && scale == 1.0 && offset == 0.0; }

  void apply(std::span<const double> in, std::span<float> out) const {
    constexpr double kFloatMax = std::numeric_limits<float>::max();
    for (std::size_t i = 0; i < in.size(); ++i) {
      double v = in[i];
      bool is_missing = false;
      for (double m : missing) is_missing = is_missing || v == m;
      if (is_missing) {
        out[i] = std::numeric_limits<float>::quiet_NaN();
        continue;
      }
      v = v * scale + offset;
      // Out-of-range doubles become ±inf explicitly (a plain cast would be undefined).
      if (v > kFloatMax) v = std::numeric_limits<double>::infinity();
      if (v < -kFloatMax) v = -std::numeric_limits<double>::infinity();
      out[i] = static_cast<float>(v);
    }
  }
};

// The values of the dimension scale (coordinate variable) attached to dimension `dim` of ds
// through its DIMENSION_LIST attribute, when it is a 1-D numeric dataset of `length` values;
// nullopt otherwise. Never throws (a scale it cannot read is ignored).
// The dimension scale dataset attached to dimension `dim` of ds through its DIMENSION_LIST
// attribute (NetCDF-4 writes one per dimension, named after it); an empty handle when there is
// none. Never throws.
Handle dimension_scale(hid_t ds, int dim) {
  if (H5Aexists(ds, "DIMENSION_LIST") <= 0) return Handle();
  Handle attr(H5Aopen(ds, "DIMENSION_LIST", H5P_DEFAULT));
  Handle space(H5Aget_space(attr.get()));
  if (!attr || !space || H5Sget_simple_extent_ndims(space.get()) != 1) return Handle();
  hsize_t n = 0;
  H5Sget_simple_extent_dims(space.get(), &n, nullptr);
  if (dim < 0 || hsize_t(dim) >= n) return Handle();
  Handle vlen(H5Tvlen_create(H5T_STD_REF_OBJ));
  std::vector<hvl_t> lists(static_cast<std::size_t>(n));
  if (H5Aread(attr.get(), vlen.get(), lists.data()) < 0) return Handle();
  Handle scale;
  const hvl_t& l = lists[std::size_t(dim)];
  if (l.len >= 1 && l.p) {
    hobj_ref_t ref = static_cast<const hobj_ref_t*>(l.p)[0];
    scale = Handle(H5Rdereference2(ds, H5P_DEFAULT, H5R_OBJECT, &ref));
    if (scale && H5Iget_type(scale.get()) != H5I_DATASET) scale = Handle();
  }
  H5Dvlen_reclaim(vlen.get(), space.get(), H5P_DEFAULT, lists.data());
  return scale;
}

// The name of dimension `dim` of ds: its dimension scale's name without the path ("" when it
// has none). Never throws.
std::string dimension_name(hid_t ds, int dim) {
  const Handle scale = dimension_scale(ds, dim);
  if (!scale) return "";
  const ssize_t n = H5Iget_name(scale.get(), nullptr, 0);
  if (n <= 0 || n > kMaxNameChars) return "";
  std::string name(std::size_t(n) + 1, '\0');
  H5Iget_name(scale.get(), name.data(), name.size());
  name.resize(std::size_t(n));
  return name.substr(name.rfind('/') + 1);
}

// A 3-D dataset whose first dimension is time (its scale named Time, time or t, as NetCDF-4
// writes WRF's and CF's): a 2-D field over time, a map, not a volume. Never throws.
bool is_map_over_time(hid_t ds, const std::vector<hsize_t>& shape) {
  if (shape.size() != 3) return false;
  std::string name = dimension_name(ds, 0);
  for (char& c : name) c = char(std::tolower(static_cast<unsigned char>(c)));
  return name == "time" || name == "t";
}

std::optional<std::vector<double>> scale_values(hid_t ds, int dim, hsize_t length) {
  const Handle scale = dimension_scale(ds, dim);
  if (!scale) return std::nullopt;
  const std::vector<hsize_t> shape = h5::dataset_shape(scale.get());
  Handle type(H5Dget_type(scale.get()));
  const H5T_class_t cls = H5Tget_class(type.get());
  if (shape.size() != 1 || shape[0] != length || (cls != H5T_FLOAT && cls != H5T_INTEGER) ||
      !is_standard_numeric_type(type.get()))
    return std::nullopt;
  std::vector<double> x(static_cast<std::size_t>(length));
  if (H5Dread(scale.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, x.data()) < 0)
    return std::nullopt;
  return x;
}

// Where the grid lies in space from the dataset's NetCDF-4 / HDF5 dimension scales (coordinate
// variables): for spatial axis a (dataset dimension first_spatial + 2 − a, x last) a 1-D
// numeric scale of the axis' length whose values step uniformly upwards (within 0.1 % of a
// step) gives origin and spacing; any other axis keeps 0 and 1. Never throws.
GridGeometry dimension_scales(hid_t ds, int first_spatial, Dims dims) {
  GridGeometry g;
  for (int a = 0; a < 3; ++a) {
    if (dims[a] < 2) continue;
    const auto x = scale_values(ds, first_spatial + 2 - a, hsize_t(dims[a]));
    if (!x) continue;
    const double step = (x->back() - x->front()) / double(x->size() - 1);
    bool uniform = std::isfinite(step) && step > 0;
    for (std::size_t i = 0; uniform && i < x->size(); ++i)
      uniform = std::fabs((*x)[i] - (x->front() + double(i) * step)) <= 1e-3 * step;
    if (!uniform) continue;
    g.origin[std::size_t(a)] = x->front();
    g.spacing[std::size_t(a)] = step;
  }
  return g;
}

// Seconds since 1970 of a WRF date "YYYY-MM-DD_HH:MM:SS" (nullopt when it is not one).
std::optional<double> wrf_date_seconds(const std::string& text) {
  std::tm tm{};
  int y = 0, mo = 0, d = 0, h = 0, mi = 0, sec = 0;
  if (std::sscanf(text.c_str(), "%4d-%2d-%2d_%2d:%2d:%2d", &y, &mo, &d, &h, &mi, &sec) != 6)
    return std::nullopt;
  tm.tm_year = y - 1900;
  tm.tm_mon = mo - 1;
  tm.tm_mday = d;
  tm.tm_hour = h;
  tm.tm_min = mi;
  tm.tm_sec = sec;
  return double(timegm(&tm));
}

// A string attribute of obj, "" when absent or not a string. Never throws.
std::string text_attribute(hid_t obj, const char* name) {
  try {
    return io::string_attribute(obj, name, name).value_or("");
  } catch (const Error&) {
    return "";
  }
}

// The physical time of each of a 4-D dataset's steps: the time dimension's coordinate variable
// when it has one value per step, increasing (its CF `units` and `calendar` into units); else
// WRF's `Times` (one date string per step) as seconds since the first step (units "seconds
// since" that date). Empty when neither (or they do not increase). Never throws.
std::vector<double> step_times(hid_t file, hid_t ds, hsize_t steps, TimeUnits& units) {
  units = {};
  auto increasing = [](const std::vector<double>& v) {
    for (std::size_t i = 0; i < v.size(); ++i)
      if (!std::isfinite(v[i]) || (i > 0 && !(v[i] > v[i - 1]))) return false;
    return !v.empty();
  };
  if (auto t = scale_values(ds, 0, steps); t && increasing(*t)) {
    const Handle scale = dimension_scale(ds, 0);
    units = {text_attribute(scale.get(), "units"), text_attribute(scale.get(), "calendar")};
    return *t;
  }
  if (H5Lexists(file, "Times", H5P_DEFAULT) <= 0) return {};
  Handle times(H5Dopen2(file, "Times", H5P_DEFAULT));
  if (!times) return {};
  const std::vector<hsize_t> shape = h5::dataset_shape(times.get());
  Handle type(H5Dget_type(times.get()));
  if (shape.size() != 2 || shape[0] != steps || shape[1] < 1 || shape[1] > 64 ||
      H5Tget_class(type.get()) != H5T_STRING || H5Tis_variable_str(type.get()) > 0 ||
      H5Tget_size(type.get()) != 1)
    return {};
  std::vector<char> chars(static_cast<std::size_t>(shape[0] * shape[1]));
  // The file's own one-byte string type: no conversion (a NULLTERM string of one byte holds
  // only its terminator, so converting NULLPAD characters to it would empty them).
  Handle mem(H5Tcopy(type.get()));
  if (H5Dread(times.get(), mem.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, chars.data()) < 0) return {};
  std::vector<double> t;
  for (hsize_t i = 0; i < steps; ++i) {
    const auto s = wrf_date_seconds(std::string(chars.data() + i * shape[1], shape[1]));
    if (!s) return {};
    t.push_back(*s);
  }
  for (std::size_t i = t.size(); i-- > 0;) t[i] -= t[0];
  if (!increasing(t) && t.size() != 1) return {};
  std::string first(chars.data(), std::size_t(shape[1]));
  for (char& c : first)
    if (c == '_') c = ' ';
  units = {"seconds since " + first, ""};
  return t;
}

// The mean over a horizontal plane of a WRF geopotential, (PH + PHB)[t = 0, level], in m²/s²;
// NaN when it cannot be read.
double mean_geopotential(hid_t file, hsize_t level, const std::vector<hsize_t>& shape) {
  const hsize_t n = shape[2] * shape[3];
  double total = 0;
  for (const char* name : {"PH", "PHB"}) {
    Handle ds(H5Dopen2(file, name, H5P_DEFAULT));
    Handle space(ds ? H5Dget_space(ds.get()) : -1);
    if (!ds || !space) return std::numeric_limits<double>::quiet_NaN();
    Handle type(H5Dget_type(ds.get()));
    if (h5::dataset_shape(ds.get()) != shape || !is_standard_numeric_type(type.get()))
      return std::numeric_limits<double>::quiet_NaN();
    const hsize_t start[4] = {0, level, 0, 0}, count[4] = {1, 1, shape[2], shape[3]};
    Handle mem(H5Screate_simple(1, &n, nullptr));
    std::vector<double> v(static_cast<std::size_t>(n));
    if (H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, start, nullptr, count, nullptr) < 0 ||
        H5Dread(ds.get(), H5T_NATIVE_DOUBLE, mem.get(), space.get(), H5P_DEFAULT, v.data()) < 0)
      return std::numeric_limits<double>::quiet_NaN();
    for (double x : v) total += x;
  }
  return total / double(n);
}

// WRF output (NetCDF-4) has no coordinate variables for its grid: the horizontal spacing is the
// global attributes DX and DY (metres), and the levels' heights follow the geopotential
// (PH + PHB)/g on the staggered levels. By default the levels are then resampled at those
// heights (wrf_heights.h, level_resample.h); as stored (--vertical-levels native) the vertical
// spacing is the mean layer thickness of the
// first step's horizontal means, (top − bottom)/(levels − 1); the levels are not evenly spaced
// (thinner near the ground), so this is their average. Origin: x, y 0 at the first mass point
// (−½ DX or DY for a field staggered along x or y), z the lowest level's mean height (half a
// layer up for mass-point variables). Leaves g alone when DX/DY are absent. True when DX and DY
// gave the horizontal spacing (the file is WRF's). Never throws (what it cannot read is ignored).
bool wrf_geometry(hid_t file, Dims dims, GridGeometry& g) {
  constexpr double kGravity = 9.81;
  const auto dx = numeric_attribute(file, "DX", "");
  const auto dy = numeric_attribute(file, "DY", "");
  if (!dx || !dy || dx->size() != 1 || dy->size() != 1 || !((*dx)[0] > 0) || !((*dy)[0] > 0) ||
      !std::isfinite((*dx)[0]) || !std::isfinite((*dy)[0]))
    return false;
  g.spacing[0] = (*dx)[0];
  g.spacing[1] = (*dy)[0];
  if (H5Lexists(file, "PH", H5P_DEFAULT) <= 0 || H5Lexists(file, "PHB", H5P_DEFAULT) <= 0) return true;
  Handle ph(H5Dopen2(file, "PH", H5P_DEFAULT));
  if (!ph) return true;
  const std::vector<hsize_t> shape = h5::dataset_shape(ph.get());
  if (shape.size() != 4 || shape[0] < 1 || shape[1] < 2 || shape[2] < 1 || shape[3] < 1) return true;
  // The horizontal plane is the grid's (or one wider, staggered): nothing larger is read.
  if (shape[2] > hsize_t(dims.y) + 1 || shape[3] > hsize_t(dims.x) + 1) return true;
  // PH's plane is the mass points'; a field one wider (U on west_east_stag, V on
  // south_north_stag) lies on the cell faces, half a cell before the first mass point.
  if (hsize_t(dims.x) == shape[3] + 1) g.origin[0] = -0.5 * g.spacing[0];
  if (hsize_t(dims.y) == shape[2] + 1) g.origin[1] = -0.5 * g.spacing[1];
  const hsize_t levels = shape[1];  // staggered: one more than the mass-point levels
  if (hsize_t(dims.z) != levels && hsize_t(dims.z) != levels - 1) return true;
  const double bottom = mean_geopotential(file, 0, shape) / kGravity;
  const double top = mean_geopotential(file, levels - 1, shape) / kGravity;
  const double dz = (top - bottom) / double(levels - 1);
  if (!std::isfinite(dz) || !(dz > 0)) return true;
  g.spacing[2] = dz;
  g.origin[2] = bottom + (hsize_t(dims.z) == levels ? 0.0 : 0.5 * dz);
  return true;
}

// The extent along dimension z_dim of a chunked dataset's chunks; 0 when it is not chunked or
// the layout cannot be read. Never throws.
int chunk_depth(hid_t dataset, int z_dim) {
  Handle dcpl(H5Dget_create_plist(dataset));
  if (!dcpl || H5Pget_layout(dcpl.get()) != H5D_CHUNKED) return 0;
  hsize_t chunk[8] = {};
  const int rank = H5Pget_chunk(dcpl.get(), 8, chunk);
  if (rank <= z_dim || chunk[z_dim] > hsize_t(INT32_MAX)) return 0;
  return int(chunk[z_dim]);
}

// One step: a dataset and, for 4-D datasets, the index along its first dimension.
struct StepRef {
  std::string dataset;
  bool indexed = false;
  hsize_t index = 0;
};

class Hdf5Source final : public VolumeSource {
 public:
  Hdf5Source(std::string path, Handle file, std::string field_text, Dims dims,
             std::vector<StepRef> steps)
      : path_(std::move(path)),
        file_(std::move(file)),
        field_text_(std::move(field_text)),
        dims_(dims),
        steps_(std::move(steps)) {}

  Dims dims() const override { return dims_; }
  int steps() const override { return int(steps_.size()); }
  std::string describe() const override { return path_ + ", " + field_text_; }
  std::string field() const override { return field_; }
  std::string field_;  // the dataset's (or the steps' group's) path without its leading '/'
  std::array<double, 3> origin() const override { return geometry_.origin; }
  std::array<double, 3> spacing() const override { return geometry_.spacing; }
  std::vector<double> times() const override { return times_; }
  TimeUnits time_units() const override { return time_units_; }
  GridGeometry geometry_;
  std::vector<double> times_;
  TimeUnits time_units_;
  std::vector<std::string> files() const override { return {path_}; }

  void read_step(int t, std::span<float> out) override { read_slab(t, 0, dims_.z, out); }
  bool reads_slabs() const override { return true; }
  int slab_alignment() const override { return chunk_planes_; }
  int chunk_planes_ = 0;  // the chunks' depth along z (0: not chunked)
  void read_slab(int t, int z0, int z1, std::span<float> out) override {
    assert(t >= 0 && t < steps() && 0 <= z0 && z0 < z1 && z1 <= dims_.z);
    assert(std::int64_t(out.size()) == std::int64_t(dims_.x) * dims_.y * (z1 - z0));
    const StepRef& step = steps_[std::size_t(t)];
    const std::string where = path_ + ", dataset " + step.dataset;
    Handle ds(H5Dopen2(file_.get(), step.dataset.c_str(), H5P_DEFAULT));
    if (!ds) throw FormatError(where + ": dataset cannot be opened");
    Packing packing = Packing::of(ds.get(), where);
    VolumeSlab slab;
    if (step.indexed) slab.fixed = {step.index};
    slab.spatial = {hsize_t(z1 - z0), hsize_t(dims_.y), hsize_t(dims_.x)};
    slab.offset = hsize_t(z0);
    BatchConverter convert;
    if (!packing.identity() || !converts_exactly_to_float(ds.get()))
      convert = [&](std::span<const double> in, std::span<float> o) { packing.apply(in, o); };
    read_volume(ds.get(), slab, out, convert, where);
  }

 private:
  std::string path_;
  Handle file_;
  std::string field_text_;
  Dims dims_;
  std::vector<StepRef> steps_;
};

std::unique_ptr<VolumeSource> open_dataset(const std::string& path, Handle file,
                                           const std::string& ds_path,
                                           const SourceOptions& options) {
  const std::string where = path + ", dataset " + ds_path;
  Handle ds(H5Dopen2(file.get(), ds_path.c_str(), H5P_DEFAULT));
  if (!ds) throw FormatError(where + ": dataset cannot be opened");
  std::vector<hsize_t> shape = h5::dataset_shape(ds.get());
  if (shape.size() != 3 && shape.size() != 4)
    throw FormatError(where + ": has rank " + std::to_string(shape.size()) + " (shape " +
                      shape_text(shape) + "), expected 3-D (Z,Y,X) or 4-D (T,Z,Y,X)");
  if (is_map_over_time(ds.get(), shape))
    throw FormatError(where + ": is a 2-D field over time (" + dimension_name(ds.get(), 0) + " " +
                      std::to_string(shape[0]) + " x " + dimension_name(ds.get(), 1) + " " +
                      std::to_string(shape[1]) + " x " + dimension_name(ds.get(), 2) + " " +
                      std::to_string(shape[2]) +
                      "): a map, not a volume; tspplay plays 3-D fields (4-D over time); "
                      "this file's: " + candidates_text(playable(list_candidates(file.get()))));
  require_numeric_dataset(ds.get(), where);
  Packing::of(ds.get(), where);  // fail now, not at the first step, on bad packing attributes
  std::vector<StepRef> steps;
  Dims dims;
  if (shape.size() == 4) {
    dims = dims_from_zyx(&shape[1], std::int64_t(std::min<hsize_t>(shape[0], INT64_MAX)), where);
    for (hsize_t t = 0; t < shape[0]; ++t) steps.push_back({ds_path, true, t});
  } else {
    dims = dims_from_zyx(&shape[0], 1, where);
    steps.push_back({ds_path, false, 0});
  }
  GridGeometry geometry = dimension_scales(ds.get(), shape.size() == 4 ? 1 : 0, dims);
  bool wrf = false;
  if (geometry.spacing == std::array<double, 3>{1, 1, 1}) {
    try {
      wrf = wrf_geometry(file.get(), dims, geometry);
    } catch (const Error&) {  // a non-numeric DX: not WRF's, ignored
    }
  }
  // WRF's levels at their heights (the geopotential per step), unless asked for as stored.
  std::optional<LevelHeightsFn> heights;
  if (wrf && shape.size() == 4 && options.vertical.mode != VerticalLevels::Mode::native)
    heights = wrf_level_heights(file.get(), dims, int(steps.size()), where);
  std::vector<double> times;
  TimeUnits units;
  if (shape.size() == 4) times = step_times(file.get(), ds.get(), shape[0], units);
  auto source = std::make_unique<Hdf5Source>(path, std::move(file), "dataset " + ds_path, dims,
                                             std::move(steps));
  source->geometry_ = geometry;
  source->field_ = ds_path.substr(std::min(ds_path.size(), ds_path.find_first_not_of('/')));
  source->times_ = std::move(times);
  source->time_units_ = std::move(units);
  source->chunk_planes_ = chunk_depth(ds.get(), shape.size() == 4 ? 1 : 0);
  if (heights)
    return resample_levels(std::move(source), std::move(*heights), options.vertical,
                           "geopotential");
  return source;
}

std::unique_ptr<VolumeSource> open_group(const std::string& path, Handle file,
                                         const std::string& group_path) {
  const std::string where = path + ", group " + group_path;
  Handle group(H5Gopen2(file.get(), group_path.c_str(), H5P_DEFAULT));
  if (!group) throw FormatError(where + ": group cannot be opened");
  std::vector<std::string> names = h5::group_members(group.get());
  if (names.empty())
    throw FormatError(where + ": is empty, expected one 3-D dataset per time step");
  natural_sort(names);
  std::vector<StepRef> steps;
  std::vector<hsize_t> first_shape;
  for (const std::string& name : names) {
    std::string member = (group_path == "/" ? "/" : group_path + "/") + name;
    const std::string mwhere = path + ", dataset " + member;
    Handle obj(H5Oopen(file.get(), member.c_str(), H5P_DEFAULT));
    if (!obj || H5Iget_type(obj.get()) != H5I_DATASET)
      throw FormatError(where + ": member " + name +
                        " is not a dataset, expected only 3-D datasets (one per step)");
    std::vector<hsize_t> shape = h5::dataset_shape(obj.get());
    if (shape.size() != 3)
      throw FormatError(mwhere + ": has rank " + std::to_string(shape.size()) + " (shape " +
                        shape_text(shape) + "), expected a 3-D (Z,Y,X) step");
    require_numeric_dataset(obj.get(), mwhere);
    Packing::of(obj.get(), mwhere);
    if (first_shape.empty()) first_shape = shape;
    if (shape != first_shape)
      throw FormatError(mwhere + ": shape " + shape_text(shape) +
                        " differs from the first step's " + shape_text(first_shape) +
                        "; all steps must have the same shape");
    steps.push_back({member, false, 0});
  }
  Dims dims = dims_from_zyx(first_shape.data(), std::int64_t(steps.size()), where);
  std::string text = "group " + group_path + " (" + std::to_string(steps.size()) + " steps)";
  GridGeometry geometry;
  int depth = 0;
  {
    Handle first(H5Dopen2(file.get(), steps[0].dataset.c_str(), H5P_DEFAULT));
    if (first) {
      geometry = dimension_scales(first.get(), 0, dims);
      depth = chunk_depth(first.get(), 0);
    }
  }
  auto source = std::make_unique<Hdf5Source>(path, std::move(file), text, dims, std::move(steps));
  source->geometry_ = geometry;
  source->field_ = group_path.substr(std::min(group_path.size(), group_path.find_first_not_of('/')));
  source->chunk_planes_ = depth;
  return source;
}

// NetCDF classic files ("CDF\x01", "CDF\x02", "CDF\x05") share the .nc extension but are not HDF5.
bool is_netcdf_classic(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[4] = {};
  in.read(magic, 4);
  return in.gcount() == 4 && magic[0] == 'C' && magic[1] == 'D' && magic[2] == 'F' &&
         (magic[3] == 1 || magic[3] == 2 || magic[3] == 5);
}

}  // namespace

h5::Handle open_hdf5_file(const std::string& path, const SourceOptions& options) {
  if (is_netcdf_classic(path))
    throw FormatError(path +
                      ": NetCDF classic (version 3) file, expected NetCDF-4/HDF5; convert "
                      "it with `nccopy -k nc4 in.nc out.nc`");
  return h5::open_file_readonly(
      path, options.allow_external ? h5::External::allow : h5::External::refuse);
}

std::string hdf5_candidates_text(hid_t file) { return candidates_text(list_candidates(file)); }

std::unique_ptr<VolumeSource> open_hdf5_source(const std::string& path,
                                               const SourceOptions& options) {
  return open_hdf5_source(path, open_hdf5_file(path, options), options);
}

std::unique_ptr<VolumeSource> open_hdf5_source(const std::string& path, Handle file,
                                               const SourceOptions& options) {
  if (is_vtkhdf(file.get())) return open_vtkhdf_source(path, std::move(file), options);

  std::string field = options.field;
  if (field.empty()) {
    std::vector<Candidate> all = list_candidates(file.get());
    std::vector<Candidate> four, three;
    for (const Candidate& c : all)
      if (!c.map_over_time) (c.shape.size() == 4 ? four : three).push_back(c);
    if (four.size() == 1) {
      field = four[0].path;
    } else if (four.empty() && three.size() == 1) {
      field = three[0].path;
    } else {
      throw FormatError(path + ": no field given and " +
                        (all.empty() ? std::string("the file holds no 3-D or 4-D dataset")
                                     : "no single 4-D dataset to default to; candidates: " +
                                           candidates_text(all)) +
                        "; name one with --field");
    }
  }
  const std::string obj_path = field[0] == '/' ? field : "/" + field;
  if (!h5::exists(file.get(), obj_path))
    throw FormatError(path + ": field '" + field + "' not found; available 3-D/4-D fields: " +
                      candidates_text(list_candidates(file.get())));
  Handle obj(H5Oopen(file.get(), obj_path.c_str(), H5P_DEFAULT));
  if (!obj) throw FormatError(path + ": field '" + field + "' cannot be opened");
  H5I_type_t kind = H5Iget_type(obj.get());
  obj.reset();
  if (kind == H5I_DATASET) return open_dataset(path, std::move(file), obj_path, options);
  if (kind == H5I_GROUP) return open_group(path, std::move(file), obj_path);
  throw FormatError(path + ": field '" + field +
                    "' is neither a dataset nor a group (a named datatype?)");
}

}  // namespace tsp::io
