#include "tsp/voxelize/open_fields.h"

#include "tsp/core/error.h"
#include "tsp/hdf5/hdf5_handle.h"
#include "tsp/hdf5/hdf5_lock.h"
#include "tsp/source/hdf5_source.h"
#include "tsp/source/mesh_file.h"
#include "tsp/source/vtkhdf_mesh_source.h"
#include "tsp/source/open_source.h"
#include "tsp/source/vtkhdf_source.h"
#include "tsp/voxelize/open_input.h"

namespace tsp {
namespace {

// One open HDF5 file; every field's source gets its own identifier of it (H5Freopen: the same
// open file, not opened or checked again).
struct SharedHdf5 {
  std::string path;
  SourceOptions options;
  h5::Handle file;

  std::unique_ptr<VolumeSource> open(const std::string& field) const {
    h5::Handle again(H5Freopen(file.get()));
    if (!again) throw IoError(path + ": cannot open the HDF5 file again for field " + field);
    SourceOptions o = options;
    o.field = field;
    return io::open_hdf5_source(path, std::move(again), o);
  }
};

// FormatError naming the fields of `fields` the file lacks, if any (a VTKHDF file's reader
// checks its own).
void require_fields(const SharedHdf5& h5file, const std::vector<std::string>& fields) {
  if (io::is_vtkhdf(h5file.file.get())) return;
  std::vector<std::string> missing;
  for (const std::string& f : fields)
    if (f.empty() || !h5::exists(h5file.file.get(), f[0] == '/' ? f : "/" + f))
      missing.push_back(f);
  if (missing.empty()) return;
  std::string list;
  for (std::size_t i = 0; i < std::min(missing.size(), kMissingFieldsListed); ++i)
    list += (i ? ", '" : "'") + missing[i] + "'";
  if (missing.size() > kMissingFieldsListed)
    list += " and " + std::to_string(missing.size() - kMissingFieldsListed) + " more";
  throw FormatError(h5file.path + ": " + std::to_string(missing.size()) + " of the " +
                    std::to_string(fields.size()) + " fields named not found: " + list +
                    "; available 3-D/4-D fields: " + io::hdf5_candidates_text(h5file.file.get()));
}

}  // namespace

FieldOpener open_input_fields(const std::string& input, const SourceOptions& options,
                              const VoxelizeOptions& voxel, const std::vector<std::string>& fields) {
  FieldOpener each = [input, options, voxel](const std::string& field) {
    SourceOptions o = options;
    o.field = field;
    return open_input(input, o, voxel);
  };
  if (!is_hdf5_input(input) || io::is_mesh_file_name(input)) return each;
  std::shared_ptr<SharedHdf5> shared;
  {
    const std::lock_guard lock(hdf5_mutex());
    shared = std::make_shared<SharedHdf5>(
        SharedHdf5{input, options, io::open_hdf5_file(input, options)});
    // A VTKHDF mesh (is_mesh_input's test, on the file already open) is voxelized per field.
    if (io::is_vtkhdf_unstructured(shared->file.get())) return each;
    require_fields(*shared, fields);
  }
  return [shared](const std::string& field) { return shared->open(field); };
}

std::vector<std::string> field_names(const std::string& field) {
  std::vector<std::string> names;
  if (field.find(',') == std::string::npos) return names;
  for (std::size_t p = 0; p <= field.size();) {
    std::size_t c = field.find(',', p);
    if (c == std::string::npos) c = field.size();
    names.push_back(field.substr(p, c - p));
    p = c + 1;
  }
  return names;
}

}  // namespace tsp
