#include "tsp/source/hdf5_writer.h"

#include <algorithm>
#include <set>
#include <utility>

#include "tsp/core/error.h"
#include "tsp/core/interrupt.h"
#include "tsp/core/temp_output.h"
#include "tsp/hdf5/hdf5_handle.h"

namespace tsp {
namespace {

namespace fs = std::filesystem;

// Attributes the writer itself sets; options.attributes may not reuse these names.
const std::set<std::string> kReservedAttributes = {"dims", "steps", "axes", "source"};

void check(herr_t status, const fs::path& path, const std::string& what) {
  if (status < 0) throw IoError(path.string() + ": HDF5 failed to " + what);
}

h5::Handle checked(hid_t id, const fs::path& path, const std::string& what) {
  if (id < 0) throw IoError(path.string() + ": HDF5 failed to " + what);
  return h5::Handle(id);
}

void write_attribute(hid_t obj, const Hdf5Attribute& a, const fs::path& path) {
  const std::string what = "write attribute '" + a.name + "'";
  if (const auto* s = std::get_if<std::string>(&a.value)) {
    h5::Handle type = checked(H5Tcopy(H5T_C_S1), path, what);
    check(H5Tset_size(type.get(), std::max<std::size_t>(1, s->size())), path, what);
    check(H5Tset_strpad(type.get(), H5T_STR_NULLTERM), path, what);
    check(H5Tset_cset(type.get(), H5T_CSET_UTF8), path, what);
    h5::Handle space = checked(H5Screate(H5S_SCALAR), path, what);
    h5::Handle attr =
        checked(H5Acreate2(obj, a.name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                path, what);
    std::string buf = *s;
    buf.resize(std::max<std::size_t>(1, s->size()), '\0');
    check(H5Awrite(attr.get(), type.get(), buf.data()), path, what);
    return;
  }
  const void* data = nullptr;
  hid_t mem_type = H5T_NATIVE_INT64, file_type = H5T_STD_I64LE;
  hsize_t count = 1;
  bool scalar = true;
  std::visit(
      [&](const auto& v) {
        using V = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<V, std::int64_t>) {
          data = &v;
        } else if constexpr (std::is_same_v<V, std::uint64_t>) {
          data = &v;
          mem_type = H5T_NATIVE_UINT64;
          file_type = H5T_STD_U64LE;
        } else if constexpr (std::is_same_v<V, double>) {
          data = &v;
          mem_type = H5T_NATIVE_DOUBLE;
          file_type = H5T_IEEE_F64LE;
        } else if constexpr (std::is_same_v<V, std::vector<std::int64_t>>) {
          data = v.data();
          count = v.size();
          scalar = false;
        }
      },
      a.value);
  h5::Handle space =
      checked(scalar ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &count, nullptr), path, what);
  h5::Handle attr =
      checked(H5Acreate2(obj, a.name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
              path, what);
  check(H5Awrite(attr.get(), mem_type, data), path, what);
}

void validate(const Hdf5WriteOptions& options) {
  const std::string& n = options.dataset;
  if (n.empty() || n.find('/') != std::string::npos || n == "." || n == "..")
    throw UsageError("HDF5 dataset name '" + n + "': expected a non-empty name without '/'");
  if (options.gzip_level < 0 || options.gzip_level > kMaxGzipLevel)
    throw UsageError("gzip level " + std::to_string(options.gzip_level) + ": expected 0.." +
                     std::to_string(kMaxGzipLevel));
  std::set<std::string> seen;
  for (const auto& a : options.attributes) {
    if (a.name.empty() || kReservedAttributes.count(a.name) || !seen.insert(a.name).second)
      throw UsageError("HDF5 attribute name '" + a.name +
                       "': expected a non-empty name, unique, and not one of dims, steps, axes, "
                       "source");
  }
}

// Writes the whole file at tmp; the caller renames or removes it.
void write_file(VolumeSource& source, const fs::path& tmp, const fs::path& shown,
                const Hdf5WriteOptions& options) {
  const Dims d = source.dims();
  const int steps = source.steps();
  // The file id is held by hand, not by h5::Handle: its close status must be checked.
  struct FileGuard {
    hid_t id;
    ~FileGuard() {
      if (id >= 0) H5Fclose(id);
    }
  } file{H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT)};
  if (file.id < 0)
    throw IoError(shown.string() + ": cannot create the file (directory not writable?)");
  const hsize_t shape[4] = {hsize_t(steps), hsize_t(d.z), hsize_t(d.y), hsize_t(d.x)};
  const std::int64_t slice_bytes = std::int64_t(d.x) * d.y * std::int64_t(sizeof(float));
  const hsize_t slab = hsize_t(std::clamp<std::int64_t>(kMaxChunkBytes / slice_bytes, 1, d.z));
  const hsize_t chunk[4] = {1, slab, hsize_t(d.y), hsize_t(d.x)};
  h5::Handle dcpl = checked(H5Pcreate(H5P_DATASET_CREATE), shown, "make a property list");
  check(H5Pset_chunk(dcpl.get(), 4, chunk), shown, "set the chunk size");
  if (options.gzip_level > 0) {
    check(H5Pset_shuffle(dcpl.get()), shown, "enable shuffle");
    check(H5Pset_deflate(dcpl.get(), unsigned(options.gzip_level)), shown, "enable gzip");
  }
  h5::Handle space = checked(H5Screate_simple(4, shape, nullptr), shown, "make the dataspace");
  const std::string what = "create dataset /" + options.dataset;
  h5::Handle dset = checked(H5Dcreate2(file.id, options.dataset.c_str(), H5T_IEEE_F32LE,
                                       space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
                            shown, what);

  std::vector<Hdf5Attribute> attrs = {
      {"dims", std::vector<std::int64_t>{d.x, d.y, d.z}},
      {"steps", std::int64_t(steps)},
      {"axes", std::string("t,z,y,x")},
      {"source", source.describe()},
  };
  attrs.insert(attrs.end(), options.attributes.begin(), options.attributes.end());
  for (const auto& a : attrs) write_attribute(dset.get(), a, shown);

  std::vector<float> buf(std::size_t(d.count()));
  const hsize_t one_step[4] = {1, hsize_t(d.z), hsize_t(d.y), hsize_t(d.x)};
  h5::Handle mem = checked(H5Screate_simple(4, one_step, nullptr), shown, "make a dataspace");
  for (int t = 0; t < steps; ++t) {
    throw_if_interrupted();  // SIGINT/SIGTERM: the temporary file is removed
    source.read_step(t, buf);
    const hsize_t start[4] = {hsize_t(t), 0, 0, 0};
    check(H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, start, nullptr, one_step, nullptr),
          shown, "select step " + std::to_string(t));
    check(H5Dwrite(dset.get(), H5T_NATIVE_FLOAT, mem.get(), space.get(), H5P_DEFAULT, buf.data()),
          shown, "write step " + std::to_string(t) + " of /" + options.dataset + " (disk full?)");
  }
  dset.reset();
  // Closing flushes: a full disk shows up here, so the status matters.
  const herr_t closed = H5Fclose(std::exchange(file.id, H5I_INVALID_HID));
  check(closed, shown, "close (flush) the file (disk full?)");
}

}  // namespace

void write_hdf5(VolumeSource& source, const fs::path& path, const Hdf5WriteOptions& options) {
  validate(options);
  h5::silence_errors();
  TempOutput out(path.string());  // checks the directory; removes the temporary file on failure
  write_file(source, out.tmp(), path, options);
  out.commit();
}

}  // namespace tsp
