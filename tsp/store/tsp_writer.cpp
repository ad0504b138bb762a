#include "tsp/store/tsp_writer.h"

#include <algorithm>
#include <cassert>
#include <mutex>
#include <vector>

#include "tsp/core/error.h"
#include "tsp/hdf5/hdf5_handle.h"
#include "tsp/hdf5/hdf5_lock.h"
#include "tsp/store/tsp_layout.h"
#include "tsp/tree/stats_columns.h"

namespace tsp {

namespace {

// Steps (chunks) written by one H5Dwrite of a brick series.
constexpr hsize_t kWriteBatchSteps = 256;

using h5::Handle;

// Throws IoError naming the file and the object when an HDF5 call failed.
hid_t check_id(hid_t id, const std::string& path, const std::string& what) {
  if (id < 0) throw IoError(path + ": cannot write " + what + " (HDF5 error; disk full?)");
  return id;
}
void check_status(herr_t status, const std::string& path, const std::string& what) {
  if (status < 0) throw IoError(path + ": cannot write " + what + " (HDF5 error; disk full?)");
}

void write_attr(hid_t loc, const std::string& path, const char* name, hid_t mem_type,
                hid_t file_type, std::vector<hsize_t> dims, const void* data) {
  Handle space(check_id(dims.empty() ? H5Screate(H5S_SCALAR)
                                     : H5Screate_simple(int(dims.size()), dims.data(), nullptr),
                        path, name));
  Handle attr(check_id(H5Acreate2(loc, name, file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                       path, std::string("attribute ") + name));
  check_status(H5Awrite(attr.get(), mem_type, data), path, std::string("attribute ") + name);
}

void write_attr_string(hid_t loc, const std::string& path, const char* name, const std::string& s) {
  // Variable-length UTF-8: h5py returns a Python str.
  Handle type(check_id(H5Tcopy(H5T_C_S1), path, name));
  H5Tset_size(type.get(), H5T_VARIABLE);
  H5Tset_cset(type.get(), H5T_CSET_UTF8);
  const char* p = s.c_str();
  write_attr(loc, path, name, type.get(), type.get(), {}, &p);
}

void write_dataset(hid_t loc, const std::string& path, const char* name, hid_t mem_type,
                   hid_t file_type, std::vector<hsize_t> dims, const void* data) {
  Handle space(check_id(H5Screate_simple(int(dims.size()), dims.data(), nullptr), path, name));
  Handle ds(
      check_id(H5Dcreate2(loc, name, file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
               path, name));
  bool empty = std::any_of(dims.begin(), dims.end(), [](hsize_t d) { return d == 0; });
  if (!empty)
    check_status(H5Dwrite(ds.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), path, name);
}

void make_group(hid_t file, const std::string& path, const char* name) {
  Handle g(check_id(H5Gcreate2(file, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), path, name));
}

std::array<int, 6> flat(const Box& b) {
  return {b.lo[0], b.lo[1], b.lo[2], b.hi[0], b.hi[1], b.hi[2]};
}

}  // namespace

struct TspWriter::Impl {
  std::string path;
  int field_index = 0;
  CollectiveIo* io = nullptr;
  Handle dxpl;  ///< with io: collective transfers
  Handle file;
  Handle loc;  ///< where this field goes: the root group, or fields/K
  Handle data;
  Handle inside;
  int steps = 0;
  std::array<int, 3> shape{};  // x, y, z
};

// Opens the location of field field_index (the root, or fields/K) in an open file. Throws IoError.
Handle open_field_group(hid_t file, const std::string& path, int field_index) {
  const std::string group = layout::field_group(field_index);
  return Handle(check_id(H5Gopen2(file, group.c_str(), H5P_DEFAULT), path, group));
}

TspWriter::TspWriter(const std::string& path, const TspTree& tree, int field_index, int deflate,
                     CollectiveIo* io)
    : impl_(std::make_unique<Impl>()) {
  assert(field_index >= 0 && deflate >= 0 && deflate <= 9);
  std::lock_guard lock(hdf5_mutex());
  h5::silence_errors();
  Impl& w = *impl_;
  w.path = path;
  w.field_index = field_index;
  w.io = io;
  w.steps = tree.time().steps();
  w.shape = stored_brick_shape(tree.octree());
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS));
  if (io) {
    io->set_file_access(fapl.get());
    w.dxpl = Handle(H5Pcreate(H5P_DATASET_XFER));
    io->set_collective_transfer(w.dxpl.get());
    if (field_index > 0) io->barrier();  // the finisher of the previous field has closed it
  }
  // The newest 1.10 structures: chunk indexes suited to fixed-size datasets. h5py reads them.
  H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_LATEST, H5F_LIBVER_LATEST);
  if (field_index == 0) {
    w.file = Handle(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()));
    if (!w.file) throw IoError(path + ": cannot create the output file");
    w.loc = open_field_group(w.file.get(), path, 0);
  } else {  // a further field of the file the first one was written to: its own group
    w.file = Handle(H5Fopen(path.c_str(), H5F_ACC_RDWR, fapl.get()));
    if (!w.file) throw IoError(path + ": cannot reopen the output file for another field");
    if (!h5::exists(w.file.get(), layout::kFieldsGroup))
      make_group(w.file.get(), path, layout::kFieldsGroup);
    const std::string group = layout::field_group(field_index);
    w.loc = Handle(check_id(H5Gcreate2(w.file.get(), group.c_str(), H5P_DEFAULT, H5P_DEFAULT,
                                       H5P_DEFAULT),
                            path, group));
  }
  const hid_t loc = w.loc.get();
  make_group(loc, path, layout::kBricks);
  make_group(loc, path, layout::kOctree);
  make_group(loc, path, layout::kTime);
  make_group(loc, path, layout::kStats);
  make_group(loc, path, layout::kLevels);

  const int nb = tree.octree().stored_brick_count();
  std::vector<hsize_t> dims = {hsize_t(nb), hsize_t(w.steps), hsize_t(w.shape[2]),
                               hsize_t(w.shape[1]), hsize_t(w.shape[0])};
  std::vector<hsize_t> chunk = {1, 1, dims[2], dims[3], dims[4]};
  Handle space(check_id(H5Screate_simple(5, dims.data(), nullptr), path, layout::kBrickData));
  Handle dcpl(H5Pcreate(H5P_DATASET_CREATE));
  H5Pset_chunk(dcpl.get(), 5, chunk.data());
  H5Pset_fill_time(dcpl.get(), H5D_FILL_TIME_NEVER);  // every chunk is written exactly once
  if (deflate > 0) {  // the 16-bit codes' high bytes together first: they compress best
    H5Pset_shuffle(dcpl.get());
    H5Pset_deflate(dcpl.get(), unsigned(deflate));
  }
  // A Fletcher-32 checksum per chunk (one brick at one step): a corrupted brick is reported by
  // HDF5 on read instead of being drawn.
  H5Pset_fletcher32(dcpl.get());
  Handle dapl(H5Pcreate(H5P_DATASET_ACCESS));
  // No chunk cache: whole chunks go straight to the file instead of being copied first.
  H5Pset_chunk_cache(dapl.get(), 0, 0, 1.0);
  w.data = Handle(check_id(H5Dcreate2(loc, layout::kBrickData, H5T_STD_U16LE, space.get(),
                                      H5P_DEFAULT, dcpl.get(), dapl.get()),
                           path, layout::kBrickData));
  if (tree.has_stencil()) {
    // The stencil compresses to almost nothing: all-inside and all-outside chunks are runs.
    Handle icpl(H5Pcreate(H5P_DATASET_CREATE));
    H5Pset_chunk(icpl.get(), 5, chunk.data());
    H5Pset_fill_time(icpl.get(), H5D_FILL_TIME_NEVER);
    H5Pset_deflate(icpl.get(), 1);
    H5Pset_fletcher32(icpl.get());
    w.inside = Handle(check_id(H5Dcreate2(loc, layout::kBrickInside, H5T_STD_U8LE,
                                          space.get(), H5P_DEFAULT, icpl.get(), H5P_DEFAULT),
                               path, layout::kBrickInside));
  }
}

TspWriter::~TspWriter() {
  std::lock_guard lock(hdf5_mutex());
  impl_->data.reset();
  impl_->inside.reset();
  impl_->loc.reset();
  impl_->file.reset();
}

void TspWriter::write_field_list(const std::string& path, const std::vector<std::string>& names) {
  std::lock_guard lock(hdf5_mutex());
  h5::silence_errors();
  std::string text;
  for (const std::string& n : names) {
    assert(n.find('\n') == std::string::npos);
    text += (text.empty() ? "" : "\n") + n;
  }
  Handle file(H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT));
  if (!file) throw IoError(path + ": cannot reopen the output file to list its fields");
  Handle root(check_id(H5Gopen2(file.get(), "/", H5P_DEFAULT), path, "/"));
  write_attr_string(root.get(), path, layout::kAttrFields, text);
  root.reset();
  if (H5Fflush(file.get(), H5F_SCOPE_GLOBAL) < 0) throw IoError(path + ": cannot flush the output file");
}

namespace {

// Writes brick's chunks at every step of a [brick, step, z, y, x] dataset from data (memory type
// mem_type, elem bytes per sample), in batches of steps, one H5Dwrite per batch (with dxpl
// collective: every process makes the same calls; brick < 0 is this process's empty part).
// Batches, because HDF5 keeps per-chunk bookkeeping for every chunk of one write (and holds on
// to it in its free lists), so one write of a long series would cost memory per step. Holds
// hdf5_mutex(). Throws IoError naming what.
void write_series(hid_t dataset, hid_t mem_type, std::size_t elem, const std::array<int, 3>& shape,
                  int steps, int brick, const void* data, hid_t dxpl, const std::string& path,
                  const std::string& what) {
  const hsize_t per_step = hsize_t(shape[0]) * shape[1] * shape[2];
  std::lock_guard lock(hdf5_mutex());
  Handle fspace(H5Dget_space(dataset));
  for (hsize_t t0 = 0; t0 < hsize_t(steps); t0 += kWriteBatchSteps) {
    const hsize_t n = std::min<hsize_t>(kWriteBatchSteps, hsize_t(steps) - t0);
    hsize_t start[5] = {hsize_t(std::max(brick, 0)), t0, 0, 0, 0};
    hsize_t count[5] = {1, n, hsize_t(shape[2]), hsize_t(shape[1]), hsize_t(shape[0])};
    H5Sselect_hyperslab(fspace.get(), H5S_SELECT_SET, start, nullptr, count, nullptr);
    // Shaped like the file's selection: HDF5 copies element by element between differently
    // shaped selections.
    Handle mspace(H5Screate_simple(5, count, nullptr));
    if (brick < 0) {
      H5Sselect_none(fspace.get());
      H5Sselect_none(mspace.get());
    }
    check_status(H5Dwrite(dataset, mem_type, mspace.get(), fspace.get(), dxpl,
                          brick < 0 ? nullptr
                                    : static_cast<const unsigned char*>(data) + t0 * per_step * elem),
                 path, what);
  }
}

}  // namespace

void TspWriter::write_brick_series(int brick, std::span<const std::uint16_t> codes) {
  const Impl& w = *impl_;
  assert(codes.size() == std::size_t(w.shape[0]) * w.shape[1] * w.shape[2] * std::size_t(w.steps));
  write_series(w.data.get(), H5T_NATIVE_UINT16, sizeof(std::uint16_t), w.shape, w.steps, brick,
               codes.data(), w.io ? w.dxpl.get() : H5P_DEFAULT, w.path,
               "brick " + std::to_string(brick));
}

void TspWriter::write_inside_series(int brick, std::span<const std::uint8_t> inside) {
  const Impl& w = *impl_;
  assert(w.inside &&
         inside.size() == std::size_t(w.shape[0]) * w.shape[1] * w.shape[2] * std::size_t(w.steps));
  write_series(w.inside.get(), H5T_NATIVE_UINT8, 1, w.shape, w.steps, brick, inside.data(),
               w.io ? w.dxpl.get() : H5P_DEFAULT, w.path, "stencil of brick " + std::to_string(brick));
}

void TspWriter::write_no_brick() {
  const Impl& w = *impl_;
  assert(w.io);
  write_series(w.data.get(), H5T_NATIVE_UINT16, sizeof(std::uint16_t), w.shape, w.steps, -1,
               nullptr, w.dxpl.get(),
               w.path, "bricks");
  if (w.inside)
    write_series(w.inside.get(), H5T_NATIVE_UINT8, 1, w.shape, w.steps, -1, nullptr,
                 w.dxpl.get(), w.path, "stencils");
}

void TspWriter::end_collective(bool finisher) {
  std::lock_guard lock(hdf5_mutex());
  Impl& w = *impl_;
  assert(w.io);
  w.data.reset();
  w.inside.reset();
  w.loc.reset();
  w.dxpl.reset();
  if (H5Fclose(w.file.release()) < 0) throw IoError(w.path + ": cannot close the output file");
  w.io = nullptr;
  if (!finisher) return;
  w.file = Handle(H5Fopen(w.path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT));
  if (!w.file) throw IoError(w.path + ": cannot reopen the output file to finish it");
  w.loc = open_field_group(w.file.get(), w.path, w.field_index);
}

namespace {

// The shape of the tree (bricks, octree, stops, stencil fractions, level bricks and their
// residuals), as the reader recomputes and checks it.
void write_shape(hid_t f, const std::string& p, const TspTree& tree) {
  const Octree& o = tree.octree();
  const int nb = o.brick_count();
  std::vector<std::array<int, 6>> samples(nb), own(nb);
  for (int b = 0; b < nb; ++b) {
    samples[b] = flat(o.brick_samples(b));
    own[b] = flat(o.brick_box(b));
  }
  write_dataset(f, p, layout::kBrickSamplesBox, H5T_NATIVE_INT32, H5T_STD_I32LE, {hsize_t(nb), 6},
                samples.data());
  write_dataset(f, p, layout::kBrickOwnBox, H5T_NATIVE_INT32, H5T_STD_I32LE, {hsize_t(nb), 6},
                own.data());
  const hsize_t no = hsize_t(o.size());
  std::vector<std::array<int, 6>> box(no);
  std::vector<std::array<int, 8>> children(no);
  std::vector<int> level(no), parent(no), brick(no);
  for (int i = 0; i < o.size(); ++i) {
    const OctreeNode& n = o.node(i);
    box[i] = flat(n.box);
    children[i] = n.children;
    level[i] = n.level;
    parent[i] = n.parent;
    brick[i] = n.brick;
  }
  write_dataset(f, p, layout::kOctreeBox, H5T_NATIVE_INT32, H5T_STD_I32LE, {no, 6}, box.data());
  write_dataset(f, p, layout::kOctreeLevel, H5T_NATIVE_INT32, H5T_STD_I32LE, {no}, level.data());
  write_dataset(f, p, layout::kOctreeParent, H5T_NATIVE_INT32, H5T_STD_I32LE, {no}, parent.data());
  write_dataset(f, p, layout::kOctreeChildren, H5T_NATIVE_INT32, H5T_STD_I32LE, {no, 8},
                children.data());
  write_dataset(f, p, layout::kOctreeBrick, H5T_NATIVE_INT32, H5T_STD_I32LE, {no}, brick.data());
  if (o.has_stops()) {
    std::vector<std::uint8_t> stopped(no);
    for (int i = 0; i < o.size(); ++i) stopped[std::size_t(i)] = o.stopped(i) ? 1 : 0;
    write_dataset(f, p, layout::kOctreeStopped, H5T_NATIVE_UINT8, H5T_STD_U8LE, {no},
                  stopped.data());
  }
  if (tree.has_stencil())
    write_dataset(f, p, layout::kOctreeInside, H5T_NATIVE_FLOAT, H5T_IEEE_F32LE, {no},
                  tree.inside_fractions().data());
  const hsize_t nl = hsize_t(o.level_brick_count());
  std::vector<int> level_node(nl);
  std::vector<std::array<int, 9>> lattice(nl);
  for (hsize_t j = 0; j < nl; ++j) {
    const int i = o.brick_count() + int(j);
    const BrickLattice l = o.lattice(i);
    level_node[j] = o.stored_brick_node(i);
    for (int a = 0; a < 3; ++a) {
      lattice[j][a] = l.origin[a];
      lattice[j][3 + a] = l.factor[a];
      lattice[j][6 + a] = l.samples[a];
    }
  }
  write_dataset(f, p, layout::kLevelNode, H5T_NATIVE_INT32, H5T_STD_I32LE, {nl}, level_node.data());
  write_dataset(f, p, layout::kLevelLattice, H5T_NATIVE_INT32, H5T_STD_I32LE, {nl, 9},
                lattice.data());
  assert(tree.level_errors().size() == nl * hsize_t(tree.time().steps()));
  write_dataset(f, p, layout::kLevelError, H5T_NATIVE_FLOAT, H5T_IEEE_F32LE,
                {nl, hsize_t(tree.time().steps())}, tree.level_errors().data());
}

// The time tree's spans and the steps' times with their units.
void write_times(hid_t f, const std::string& p, const TimeTree& time, const TspMetadata& meta) {
  std::vector<std::array<int, 2>> spans(time.size());
  for (int i = 0; i < time.size(); ++i) spans[i] = {time.span(i).t0, time.span(i).t1};
  write_dataset(f, p, layout::kTimeSpan, H5T_NATIVE_INT32, H5T_STD_I32LE, {hsize_t(time.size()), 2},
                spans.data());
  if (!meta.times.empty()) {
    assert(meta.times.size() == std::size_t(time.steps()));
    write_dataset(f, p, layout::kTimeValues, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE,
                  {hsize_t(meta.times.size())}, meta.times.data());
    const auto units_attr = [&](const char* name, const std::string& text) {
      if (text.empty()) return;
      Handle values(check_id(H5Dopen2(f, layout::kTimeValues, H5P_DEFAULT), p, layout::kTimeValues));
      write_attr_string(values.get(), p, name, text);
    };
    units_attr(layout::kAttrTimeUnits, meta.time_units.units);
    units_attr(layout::kAttrTimeCalendar, meta.time_units.calendar);
  }

}

// Statistics by TSP node id, and the histogram.
void write_stats(hid_t f, const std::string& p, const TspTree& tree, const TspMetadata& meta) {
  const std::size_t n = std::size_t(tree.size());
  const auto [mean, sd, mn, mx, es, et] = stats_columns(tree);
  write_dataset(f, p, layout::kStatsMean, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, {n}, mean.data());
  write_dataset(f, p, layout::kStatsStd, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, {n}, sd.data());
  write_dataset(f, p, layout::kStatsMin, H5T_NATIVE_FLOAT, H5T_IEEE_F32LE, {n}, mn.data());
  write_dataset(f, p, layout::kStatsMax, H5T_NATIVE_FLOAT, H5T_IEEE_F32LE, {n}, mx.data());
  write_dataset(f, p, layout::kStatsSpatial, H5T_NATIVE_FLOAT, H5T_IEEE_F32LE, {n}, es.data());
  write_dataset(f, p, layout::kStatsTemporal, H5T_NATIVE_FLOAT, H5T_IEEE_F32LE, {n}, et.data());
  assert(meta.histogram.size() == std::size_t(kHistogramBins));
  write_dataset(f, p, layout::kHistogram, H5T_NATIVE_UINT64, H5T_STD_U64LE,
                {hsize_t(meta.histogram.size())}, meta.histogram.data());

}

// The location's attributes: format, version, grid, ranges, build and rules.
void write_attributes(hid_t f, const std::string& p, const TspTree& tree,
                      const TspMetadata& meta) {
  const Octree& o = tree.octree();
  const Dims d = o.dims();
  const TimeTree& time = tree.time();
  hid_t r = f;
  const int version = o.has_stops() ? kTspAdaptiveFormatVersion : kTspFormatVersion, steps = time.steps(), bs = o.brick_size();
  const int dims[3] = {d.x, d.y, d.z};
  const ValueRange vr = tree.value_range();
  const double value_range[2] = {vr.lo, vr.hi};
  const double data_range[2] = {meta.data_range.lo, meta.data_range.hi};
  const std::int64_t nonfinite = meta.nonfinite_count;
  write_attr_string(r, p, layout::kAttrFormat, layout::kFormatName);
  write_attr(r, p, layout::kAttrVersion, H5T_NATIVE_INT, H5T_STD_I32LE, {}, &version);
  write_attr(r, p, layout::kAttrDims, H5T_NATIVE_INT, H5T_STD_I32LE, {3}, dims);
  write_attr(r, p, layout::kAttrSteps, H5T_NATIVE_INT, H5T_STD_I32LE, {}, &steps);
  write_attr(r, p, layout::kAttrBrickSize, H5T_NATIVE_INT, H5T_STD_I32LE, {}, &bs);
  write_attr(r, p, layout::kAttrValueRange, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, {2}, value_range);
  write_attr(r, p, layout::kAttrDataRange, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, {2}, data_range);
  write_attr(r, p, layout::kAttrNonfinite, H5T_NATIVE_INT64, H5T_STD_I64LE, {}, &nonfinite);
  write_attr(r, p, layout::kAttrBuildRanks, H5T_NATIVE_INT, H5T_STD_I32LE, {}, &meta.build_ranks);
  write_attr(r, p, layout::kAttrOrigin, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, {3}, meta.origin.data());
  write_attr(r, p, layout::kAttrSpacing, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, {3},
             meta.spacing.data());
  write_attr_string(r, p, layout::kAttrSource, meta.source);
  write_attr_string(r, p, layout::kAttrField, meta.field);
  write_attr_string(r, p, layout::kAttrCreatedBy, meta.created_by);
  write_attr_string(r, p, layout::kAttrQuantization, layout::kQuantizationRule);
  write_attr_string(r, p, layout::kAttrNodeId, layout::kNodeIdRule);
  write_attr_string(r, p, layout::kAttrLevelRule, layout::kLevelRule);

}

}  // namespace

void TspWriter::finish(const TspTree& tree, const TspMetadata& meta) {
  std::lock_guard lock(hdf5_mutex());
  Impl& w = *impl_;
  const std::string& p = w.path;
  hid_t f = w.loc.get();
  write_shape(f, p, tree);
  write_times(f, p, tree.time(), meta);
  write_stats(f, p, tree, meta);
  // The location's attributes last: a file cut short before this point has no format tag and
  // is rejected.
  write_attributes(f, p, tree, meta);
  w.data.reset();
  w.inside.reset();
  if (H5Fflush(w.file.get(), H5F_SCOPE_GLOBAL) < 0)
    throw IoError(p + ": cannot flush the output file");
  w.loc.reset();
  w.file.reset();
}

}  // namespace tsp
