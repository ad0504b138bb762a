#include "tsp/store/tsp_file.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <mutex>
#include <sstream>

#include "tsp/core/error.h"
#include "tsp/core/geometry.h"
#include "tsp/hdf5/hdf5_handle.h"
#include "tsp/hdf5/hdf5_lock.h"
#include "tsp/hdf5/hdf5_values.h"
#include "tsp/store/tsp_layout.h"
#include "tsp/store/tsp_reader.h"
#include "tsp/tree/stats_columns.h"

namespace tsp {

namespace {

using detail::Reader;
using h5::Handle;

void append_box(std::vector<int>& v, const Box& b) {
  v.insert(v.end(), {b.lo[0], b.lo[1], b.lo[2], b.hi[0], b.hi[1], b.hi[2]});
}

}  // namespace

struct TspFile::Impl {
  std::string path;
  Handle file;
  Handle loc;  ///< the field's location: the root group, or fields/K
  std::vector<std::string> fields;
  int field_index = 0;
  Handle data;
  Handle inside;
  std::unique_ptr<TspTree> tree;
  TspMetadata meta;
  Aabb frame;  ///< every field's physical box, united
};

TspFile::TspFile(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

TspFile::~TspFile() {
  std::lock_guard lock(hdf5_mutex());
  impl_->data.reset();
  impl_->inside.reset();
  impl_->loc.reset();
  impl_->file.reset();
}

namespace {

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> out;
  std::size_t p = 0;
  while (p <= text.size()) {
    std::size_t n = text.find('\n', p);
    if (n == std::string::npos) n = text.size();
    out.push_back(text.substr(p, n - p));
    p = n + 1;
  }
  return out;
}

}  // namespace

namespace {

// The fields (the root's own, then fields/1, fields/2, …: files with several), the one asked
// for (empty: the first) and its location. Returns its path prefix for messages.
std::string select_field(TspFile::Impl* impl, Handle& root_group, const Reader& root,
                         const std::string& path, const std::string& field) {
  impl->fields = root.has_attr(layout::kAttrFields)
                     ? split_lines(root.attr_string(layout::kAttrFields))
                     : std::vector<std::string>{root.attr_string(layout::kAttrField)};
  {  // sorted, so the check costs n log n (a hostile file may list 150,000 names)
    std::vector<std::string> sorted = impl->fields;
    std::sort(sorted.begin(), sorted.end());
    const auto twice = std::adjacent_find(sorted.begin(), sorted.end());
    if (twice != sorted.end())
      root.fail("attribute fields", "the field '" + *twice + "' is listed twice");
  }
  if (!field.empty()) {
    const auto it = std::find(impl->fields.begin(), impl->fields.end(), field);
    if (it == impl->fields.end()) {
      std::string names;
      for (const std::string& f : impl->fields) names += (names.empty() ? "" : ", ") + f;
      throw UsageError("--field " + field + ": " + path + " holds the field(s) " + names);
    }
    impl->field_index = int(it - impl->fields.begin());
  }
  std::string prefix = "/";
  if (impl->field_index == 0) {
    impl->loc = std::move(root_group);
  } else {
    const std::string group = layout::field_group(impl->field_index);
    if (!h5::exists(impl->file.get(), group.c_str()))
      root.fail("group /" + group, "missing (the field '" + field + "' is listed but not stored)");
    impl->loc = Handle(H5Gopen2(impl->file.get(), group.c_str(), H5P_DEFAULT));
    if (!impl->loc) root.fail("group /" + group, "cannot be opened");
    prefix = "/" + group + "/";
  }
  return prefix;
}

// The grid and tree (dims, steps, brick size), the value and data ranges and the build's
// attributes.
void read_grid(TspFile::Impl* impl, const Reader& r, const Reader& root, const std::string& path) {
  auto dims = r.attr_numbers<int>(layout::kAttrDims, H5T_NATIVE_INT, 3);
  const int steps = r.attr_numbers<int>(layout::kAttrSteps, H5T_NATIVE_INT, 1)[0];
  const int brick = r.attr_numbers<int>(layout::kAttrBrickSize, H5T_NATIVE_INT, 1)[0];
  // Fields may lie on different grids (their own dims, origin, spacing, brick size) but play
  // over the same steps.
  if (impl->field_index > 0 && steps != root.attr_numbers<int>(layout::kAttrSteps, H5T_NATIVE_INT, 1)[0])
    r.fail("attribute steps", "differs from the file's first field");
  if (steps < 1) r.fail("attribute steps", "expected at least 1, found " + std::to_string(steps));
  check_grid(dims[0], dims[1], dims[2], steps, path + ": attributes dims/steps");
  try {
    impl->tree = std::make_unique<TspTree>(Dims{dims[0], dims[1], dims[2]}, steps, brick);
  } catch (const UsageError& e) {
    r.fail("attributes dims/brick_size", e.what());
  }
  TspTree& tree = *impl->tree;
  auto vr = r.attr_numbers<double>(layout::kAttrValueRange, H5T_NATIVE_DOUBLE, 2);
  if (!std::isfinite(vr[0]) || !std::isfinite(vr[1]) || vr[0] > vr[1])
    r.fail("attribute value_range", "expected finite lo <= hi");
  tree.set_value_range({vr[0], vr[1]});
  auto dr = r.attr_numbers<double>(layout::kAttrDataRange, H5T_NATIVE_DOUBLE, 2);
  TspMetadata& m = impl->meta;
  m.data_range = {dr[0], dr[1]};
  if (!std::isfinite(dr[0]) || !std::isfinite(dr[1]) || dr[0] > dr[1])
    r.fail("attribute data_range", "expected finite lo <= hi, found [" + std::to_string(dr[0]) +
                                       ", " + std::to_string(dr[1]) + "]");
  m.nonfinite_count = r.attr_numbers<std::int64_t>(layout::kAttrNonfinite, H5T_NATIVE_INT64, 1)[0];
  if (m.nonfinite_count < 0)
    r.fail("attribute nonfinite_count",
           "expected a count >= 0, found " + std::to_string(m.nonfinite_count));
  m.source = r.attr_string(layout::kAttrSource);
  m.field = r.attr_string(layout::kAttrField);
  m.created_by = r.attr_string(layout::kAttrCreatedBy);
  if (r.has_attr(layout::kAttrBuildRanks)) {
    m.build_ranks = r.attr_numbers<int>(layout::kAttrBuildRanks, H5T_NATIVE_INT, 1)[0];
    if (m.build_ranks < 1)
      r.fail("attribute build_ranks", "expected 1 or more, found " + std::to_string(m.build_ranks));
  }

}

// The octree and time tree as stored must be the ones the dims and brick size produce, stopped
// where the file says (version 3 only); the level bricks' residuals.
void check_layout(TspFile::Impl* impl, const Reader& r) {
  TspTree& tree = *impl->tree;
  const int steps = tree.time().steps();
  const Octree& o = tree.octree();
  const hsize_t nb = hsize_t(o.brick_count()), no = hsize_t(o.size());
  {
    const int version = r.attr_numbers<int>(layout::kAttrVersion, H5T_NATIVE_INT, 1)[0];
    const bool has_stops = H5Lexists(impl->loc.get(), layout::kOctreeStopped, H5P_DEFAULT) > 0;
    if (has_stops != (version == kTspAdaptiveFormatVersion))
      r.fail(layout::kOctreeStopped, has_stops ? "present in a version 2 file"
                                               : "missing (version 3 files have one)");
    if (has_stops) {
      auto stopped =
          r.dataset<std::uint8_t>(layout::kOctreeStopped, {no}, H5T_NATIVE_UINT8, H5T_INTEGER);
      for (std::size_t i = 0; i < stopped.size(); ++i)
        if (stopped[i] > 1)
          r.fail(r.dataset_name(layout::kOctreeStopped),
                 "element " + std::to_string(i) + " is " + std::to_string(int(stopped[i])) +
                     ", expected 0 or 1");
      tree.stop_at(stopped);
    }
  }
  std::vector<int> samples, own, box, level, parent, children, leaf_brick, spans;
  for (int b = 0; b < o.brick_count(); ++b) {
    append_box(samples, o.brick_samples(b));
    append_box(own, o.brick_box(b));
  }
  for (int i = 0; i < o.size(); ++i) {
    const OctreeNode& n = o.node(i);
    append_box(box, n.box);
    level.push_back(n.level);
    parent.push_back(n.parent);
    children.insert(children.end(), n.children.begin(), n.children.end());
    leaf_brick.push_back(n.brick);
  }
  const TimeTree& time = tree.time();
  for (int i = 0; i < time.size(); ++i)
    spans.insert(spans.end(), {time.span(i).t0, time.span(i).t1});
  auto ints = [&](const char* name, std::vector<hsize_t> shape, const std::vector<int>& want) {
    r.expect_equal(name, r.dataset<int>(name, shape, H5T_NATIVE_INT, H5T_INTEGER), want);
  };
  ints(layout::kBrickSamplesBox, {nb, 6}, samples);
  ints(layout::kBrickOwnBox, {nb, 6}, own);
  ints(layout::kOctreeBox, {no, 6}, box);
  ints(layout::kOctreeLevel, {no}, level);
  ints(layout::kOctreeParent, {no}, parent);
  ints(layout::kOctreeChildren, {no, 8}, children);
  ints(layout::kOctreeBrick, {no}, leaf_brick);
  ints(layout::kTimeSpan, {hsize_t(time.size()), 2}, spans);
  const hsize_t nl = hsize_t(o.level_brick_count());
  std::vector<int> level_node, lattice;
  for (int j = 0; j < int(nl); ++j) {
    const int i = o.brick_count() + j;
    const BrickLattice l = o.lattice(i);
    level_node.push_back(o.stored_brick_node(i));
    lattice.insert(lattice.end(), l.origin.begin(), l.origin.end());
    lattice.insert(lattice.end(), l.factor.begin(), l.factor.end());
    lattice.insert(lattice.end(), l.samples.begin(), l.samples.end());
  }
  ints(layout::kLevelNode, {nl}, level_node);
  ints(layout::kLevelLattice, {nl, 9}, lattice);
  auto level_error = r.dataset<float>(layout::kLevelError, {nl, hsize_t(steps)}, H5T_NATIVE_FLOAT,
                                      H5T_FLOAT);
  for (std::size_t i = 0; i < level_error.size(); ++i)
    if (!std::isfinite(level_error[i]) || level_error[i] < 0)
      r.fail(r.dataset_name(layout::kLevelError),
             "element " + std::to_string(i) + " is " + std::to_string(level_error[i]) +
                 ", expected a finite RMS residual >= 0");
  std::copy(level_error.begin(), level_error.end(), tree.level_errors().begin());

}

// The stencil's inside fractions, the physical origin and spacing and the steps' times. Returns
// whether the file has a stencil.
bool read_geometry(TspFile::Impl* impl, const Reader& r) {
  TspTree& tree = *impl->tree;
  TspMetadata& m = impl->meta;
  const int steps = tree.time().steps();
  const hsize_t no = hsize_t(tree.octree().size());
  const bool stencil = H5Lexists(impl->loc.get(), layout::kOctreeInside, H5P_DEFAULT) > 0;
  if (stencil) {
    auto inside = r.dataset<float>(layout::kOctreeInside, {no}, H5T_NATIVE_FLOAT, H5T_FLOAT);
    for (std::size_t i = 0; i < inside.size(); ++i)
      if (!(inside[i] >= 0 && inside[i] <= 1))
        r.fail(r.dataset_name(layout::kOctreeInside),
               "element " + std::to_string(i) + " is " + std::to_string(inside[i]) +
                   ", expected a fraction in [0, 1]");
    tree.set_inside_fractions(std::move(inside));
  }
  if (r.has_attr(layout::kAttrOrigin) || r.has_attr(layout::kAttrSpacing)) {
    auto org = r.attr_numbers<double>(layout::kAttrOrigin, H5T_NATIVE_DOUBLE, 3);
    auto sp = r.attr_numbers<double>(layout::kAttrSpacing, H5T_NATIVE_DOUBLE, 3);
    for (int a = 0; a < 3; ++a) {
      m.origin[a] = org[a];
      m.spacing[a] = sp[a];
    }
    if (const std::string why = spacing_problem(m.origin, m.spacing); !why.empty())
      r.fail("attributes origin/spacing", "expected finite values and spacings that can be drawn: " + why);
  }

  if (H5Lexists(impl->loc.get(), layout::kTimeValues, H5P_DEFAULT) > 0) {
    m.times = r.dataset<double>(layout::kTimeValues, {hsize_t(steps)}, H5T_NATIVE_DOUBLE, H5T_FLOAT);
    for (std::size_t i = 0; i < m.times.size(); ++i)
      if (!std::isfinite(m.times[i]))
        r.fail(r.dataset_name(layout::kTimeValues),
               "element " + std::to_string(i) + " is not a finite time");
    // Optional text attributes of the times (files written before them have none).
    Handle values(H5Dopen2(impl->loc.get(), layout::kTimeValues, H5P_DEFAULT));
    for (auto [name, to] : {std::pair{layout::kAttrTimeUnits, &m.time_units.units},
                            std::pair{layout::kAttrTimeCalendar, &m.time_units.calendar}})
      if (values && H5Aexists(values.get(), name) > 0)
        *to = io::string_attribute(values.get(), name, r.dataset_name(layout::kTimeValues)).value_or("");
  }

  return stencil;
}

// Every node's statistics, checked to be what the builder can write.
void read_stats(TspTree& tree, const Reader& r, bool stencil) {
  const std::vector<hsize_t> n = {hsize_t(tree.size())};
  const StatsColumns c{r.dataset<double>(layout::kStatsMean, n, H5T_NATIVE_DOUBLE, H5T_FLOAT),
                       r.dataset<double>(layout::kStatsStd, n, H5T_NATIVE_DOUBLE, H5T_FLOAT),
                       r.dataset<float>(layout::kStatsMin, n, H5T_NATIVE_FLOAT, H5T_FLOAT),
                       r.dataset<float>(layout::kStatsMax, n, H5T_NATIVE_FLOAT, H5T_FLOAT),
                       r.dataset<float>(layout::kStatsSpatial, n, H5T_NATIVE_FLOAT, H5T_FLOAT),
                       r.dataset<float>(layout::kStatsTemporal, n, H5T_NATIVE_FLOAT, H5T_FLOAT)};
  const auto& [mean, sd, mn, mx, es, et] = c;
  // Statistics the builder can write: finite, σ ≥ 0, min ≤ max, errors ≥ 0, the mean inside
  // [min, max] (up to rounding).
  for (int i = 0; i < tree.size(); ++i) {
    // With a stencil, a node wholly outside the data carries the empty marker.
    if (stencil && mn[i] == std::numeric_limits<float>::infinity() &&
        mx[i] == -std::numeric_limits<float>::infinity() && mean[i] == 0 && sd[i] == 0)
      continue;
    const double tol = 1e-6 * std::max({1.0, std::fabs(double(mn[i])), std::fabs(double(mx[i]))});
    const bool ok = std::isfinite(mean[i]) && std::isfinite(sd[i]) && sd[i] >= 0 &&
                    std::isfinite(mn[i]) && std::isfinite(mx[i]) && mn[i] <= mx[i] &&
                    mean[i] >= mn[i] - tol && mean[i] <= mx[i] + tol && std::isfinite(es[i]) &&
                    es[i] >= 0 && std::isfinite(et[i]) && et[i] >= 0;
    if (!ok)
      r.fail("statistics of TSP node " + std::to_string(i),
             "expected finite values with std >= 0, min <= mean <= max and errors >= 0, found "
             "mean " + std::to_string(mean[i]) + ", std " + std::to_string(sd[i]) + ", min " +
                 std::to_string(mn[i]) + ", max " + std::to_string(mx[i]) + ", e_s " +
                 std::to_string(es[i]) + ", e_t " + std::to_string(et[i]));
  }
  set_stats(tree, c);
}

// The bricks' datasets (scalar codes, the stencil's flags) and the histogram.
void open_bricks(TspFile::Impl* impl, const Reader& r, bool stencil) {
  const Octree& o = impl->tree->octree();
  TspMetadata& m = impl->meta;
  const int steps = impl->tree->time().steps();
  const hsize_t ns = hsize_t(o.stored_brick_count());
  m.histogram = r.dataset<std::uint64_t>(layout::kHistogram, {hsize_t(kHistogramBins)},
                                         H5T_NATIVE_UINT64, H5T_INTEGER);

  auto shape = stored_brick_shape(o);
  impl->data = r.open_dataset(
      layout::kBrickData,
      {ns, hsize_t(steps), hsize_t(shape[2]), hsize_t(shape[1]), hsize_t(shape[0])}, H5T_INTEGER);
  Handle type(H5Dget_type(impl->data.get()));
  if (H5Tget_size(type.get()) != 2 || H5Tget_sign(type.get()) != H5T_SGN_NONE)
    r.fail(r.dataset_name(layout::kBrickData), "expected 16-bit unsigned codes");
  {  // build --compress: the deflate filter's level, if any
    Handle dcpl(H5Dget_create_plist(impl->data.get()));
    unsigned flags = 0, values[1] = {0};
    std::size_t count = 1;
    if (dcpl && H5Pget_filter_by_id2(dcpl.get(), H5Z_FILTER_DEFLATE, &flags, &count, values, 0,
                                     nullptr, nullptr) >= 0)
      m.deflate = count > 0 ? int(values[0]) : 1;
  }
  if (stencil) {
    impl->inside = r.open_dataset(
        layout::kBrickInside,
        {ns, hsize_t(steps), hsize_t(shape[2]), hsize_t(shape[1]), hsize_t(shape[0])},
        H5T_INTEGER);
    Handle itype(H5Dget_type(impl->inside.get()));
    if (H5Tget_size(itype.get()) != 1)
      r.fail(r.dataset_name(layout::kBrickInside), "expected 8-bit flags");
  }
}

// The frame: this field's box, united with every other field's (attributes only; a field whose
// group is missing or broken is that field's error when it is opened, not this one's).
Aabb united_frame(const TspFile::Impl* impl, const Reader& r) {
  Aabb frame = detail::field_box(r);
  const std::string& path = impl->path;
  for (std::size_t k = 0; k < impl->fields.size(); ++k) {
    if (int(k) == impl->field_index) continue;
    const std::string group = k == 0 ? std::string("/") : layout::field_group(int(k));
    if (k > 0 && !h5::exists(impl->file.get(), group.c_str())) continue;
    Handle g(H5Gopen2(impl->file.get(), group.c_str(), H5P_DEFAULT));
    if (!g) continue;
    try {
      const Aabb b = field_box(Reader(path, g.get(), k == 0 ? "/" : "/" + group + "/"));
      for (int a = 0; a < 3; ++a) {
        frame.lo[a] = std::min(frame.lo[a], b.lo[a]);
        frame.hi[a] = std::max(frame.hi[a], b.hi[a]);
      }
    } catch (const FormatError&) {
    }
  }
  return frame;
}

}  // namespace

std::unique_ptr<TspFile> TspFile::open(const std::string& path, const std::string& field) {
  std::lock_guard lock(hdf5_mutex());
  auto impl = std::make_unique<Impl>();
  impl->path = path;
  impl->file = h5::open_file_readonly(path);
  Handle root_group(H5Gopen2(impl->file.get(), "/", H5P_DEFAULT));
  const Reader root(path, root_group.get());
  detail::check_format(root, path);
  const std::string prefix = select_field(impl.get(), root_group, root, path, field);
  const Reader r(path, impl->loc.get(), prefix);
  if (impl->field_index > 0) detail::check_format(r, path);
  read_grid(impl.get(), r, root, path);
  check_layout(impl.get(), r);
  const bool stencil = read_geometry(impl.get(), r);
  read_stats(*impl->tree, r, stencil);
  open_bricks(impl.get(), r, stencil);
  impl->frame = united_frame(impl.get(), r);
  return std::unique_ptr<TspFile>(new TspFile(std::move(impl)));
}

const TspTree& TspFile::tree() const {
  return *impl_->tree;
}
const TspMetadata& TspFile::metadata() const {
  return impl_->meta;
}
const std::string& TspFile::path() const {
  return impl_->path;
}
const std::vector<std::string>& TspFile::fields() const {
  return impl_->fields;
}
const Aabb& TspFile::frame() const { return impl_->frame; }

int TspFile::field_index() const {
  return impl_->field_index;
}

namespace {

// One stored brick of a [brick, step, z, y, x] dataset into out (its lattice's samples, memory
// type mem_type); the caller holds hdf5_mutex(). Throws FormatError starting with `what` ("FILE:
// dataset D: brick N at step T") when the brick has no chunk (HDF5 would hand back its fill
// value, zeros, as if they were data) or cannot be read, with `why` the likely cause.
void read_chunk(hid_t dataset, hid_t mem_type, const BrickLattice& s, int brick, int step,
                void* out, const std::string& what, const std::string& why) {
  hsize_t start[5] = {hsize_t(brick), hsize_t(step), 0, 0, 0};
  hsize_t count[5] = {1, 1, hsize_t(s.samples[2]), hsize_t(s.samples[1]), hsize_t(s.samples[0])};
  unsigned filters = 0;
  haddr_t address = HADDR_UNDEF;
  hsize_t stored = 0;
  if (H5Dget_chunk_info_by_coord(dataset, start, &filters, &address, &stored) >= 0 &&
      (address == HADDR_UNDEF || stored == 0))
    throw FormatError(what + " is marked present but has no stored chunk (the file is "
                             "incomplete, or was not written by tspplay)");
  Handle fspace(H5Dget_space(dataset));
  Handle mspace(H5Screate_simple(3, count + 2, nullptr));
  if (H5Sselect_hyperslab(fspace.get(), H5S_SELECT_SET, start, nullptr, count, nullptr) < 0 ||
      H5Dread(dataset, mem_type, mspace.get(), fspace.get(), H5P_DEFAULT, out) < 0)
    throw FormatError(what + ": cannot be read (" + why + ")");
}

// The samples of lattice `to` made up from the samples of the coarser lattice `from` that covers
// them: trilinear in from's samples (clamped to its last one), rounded; flags (0/1) by nearest.
template <class T>
void resample_lattice(std::span<const T> in, const BrickLattice& from, const BrickLattice& to,
                      std::span<T> out, bool nearest) {
  std::array<std::vector<int>, 3> i0;
  std::array<std::vector<float>, 3> w;
  for (int a = 0; a < 3; ++a)
    for (int j = 0; j < to.samples[a]; ++j) {
      const double u = std::clamp(double(to.origin[a] + j * to.factor[a] - from.origin[a]) /
                                      from.factor[a], 0.0, double(from.samples[a] - 1));
      const int k = std::min(int(u), std::max(from.samples[a] - 2, 0));
      i0[a].push_back(k);
      w[a].push_back(from.samples[a] > 1 ? float(u - k) : 0.f);
    }
  const std::size_t sx = std::size_t(from.samples[0]), sxy = sx * std::size_t(from.samples[1]);
  const int hx = from.samples[0] > 1, hy = from.samples[1] > 1, hz = from.samples[2] > 1;
  std::size_t o = 0;
  for (int z = 0; z < to.samples[2]; ++z)
    for (int y = 0; y < to.samples[1]; ++y)
      for (int x = 0; x < to.samples[0]; ++x, ++o) {
        const std::size_t base = std::size_t(i0[0][x]) + sx * i0[1][y] + sxy * i0[2][z];
        const float wx = w[0][x], wy = w[1][y], wz = w[2][z];
        if (nearest) {
          out[o] = in[base + (wx >= 0.5f ? hx : 0) + (wy >= 0.5f ? hy * sx : 0) +
                      (wz >= 0.5f ? hz * sxy : 0)];
          continue;
        }
        auto at = [&](int dx, int dy, int dz) {
          return float(in[base + dx * hx + dy * hy * sx + dz * hz * sxy]);
        };
        const float c00 = at(0, 0, 0) + wx * (at(1, 0, 0) - at(0, 0, 0));
        const float c10 = at(0, 1, 0) + wx * (at(1, 1, 0) - at(0, 1, 0));
        const float c01 = at(0, 0, 1) + wx * (at(1, 0, 1) - at(0, 0, 1));
        const float c11 = at(0, 1, 1) + wx * (at(1, 1, 1) - at(0, 1, 1));
        const float c0 = c00 + wy * (c10 - c00), c1 = c01 + wy * (c11 - c01);
        out[o] = T(std::lround(c0 + wz * (c1 - c0)));
      }
}

}  // namespace

void TspFile::read_brick(int brick, int step, std::span<std::uint16_t> out) const {
  const Octree& o = impl_->tree->octree();
  assert(brick >= 0 && brick < o.stored_brick_count() && step >= 0 &&
         step < impl_->tree->time().steps());
  const BrickLattice s = o.lattice(brick);
  assert(std::int64_t(out.size()) == s.count());
  if (!o.brick_present(brick)) {  // below a stop: made up from the stopped node's brick
    const int from = o.node_brick(o.stop_above(o.stored_brick_node(brick)));
    std::vector<std::uint16_t> coarse(std::size_t(o.lattice(from).count()));
    read_brick(from, step, coarse);
    resample_lattice<std::uint16_t>(coarse, o.lattice(from), s, out, false);
    return;
  }
  std::lock_guard lock(hdf5_mutex());
  read_chunk(impl_->data.get(), H5T_NATIVE_UINT16, s, brick, step, out.data(),
             impl_->path + ": dataset " + layout::kBrickData + ": brick " +
                 std::to_string(brick) + " at step " + std::to_string(step),
             "checksum mismatch: the brick is corrupted, or the file is truncated");
}

void TspFile::read_inside(int brick, int step, std::span<std::uint8_t> out) const {
  const Octree& o = impl_->tree->octree();
  assert(impl_->inside && brick >= 0 && brick < o.stored_brick_count() && step >= 0 &&
         step < impl_->tree->time().steps());
  const BrickLattice s = o.lattice(brick);
  assert(std::int64_t(out.size()) == s.count());
  if (!o.brick_present(brick)) {
    const int from = o.node_brick(o.stop_above(o.stored_brick_node(brick)));
    std::vector<std::uint8_t> coarse(std::size_t(o.lattice(from).count()));
    read_inside(from, step, coarse);
    resample_lattice<std::uint8_t>(coarse, o.lattice(from), s, out, true);
    return;
  }
  std::lock_guard lock(hdf5_mutex());
  read_chunk(impl_->inside.get(), H5T_NATIVE_UINT8, s, brick, step, out.data(),
             impl_->path + ": dataset " + layout::kBrickInside + ": the stencil of brick " +
                 std::to_string(brick) + " at step " + std::to_string(step),
             "corrupted or truncated");
}

}  // namespace tsp
