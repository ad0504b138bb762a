#include "tsp/hdf5/hdf5_handle.h"

#include <atomic>
#include <filesystem>

#include "tsp/core/error.h"
#include "tsp/core/file_check.h"

namespace tsp::h5 {

void Handle::reset() {
  if (id_ < 0) return;
  switch (H5Iget_type(id_)) {
    case H5I_FILE: H5Fclose(id_); break;
    case H5I_GROUP: H5Gclose(id_); break;
    case H5I_DATASET: H5Dclose(id_); break;
    case H5I_DATASPACE: H5Sclose(id_); break;
    case H5I_DATATYPE: H5Tclose(id_); break;
    case H5I_ATTR: H5Aclose(id_); break;
    case H5I_GENPROP_LST: H5Pclose(id_); break;
    default: H5Idec_ref(id_); break;
  }
  id_ = H5I_INVALID_HID;
}

namespace {
std::atomic<std::int64_t> g_files_opened{0};
}  // namespace

std::int64_t files_opened() { return g_files_opened.load(); }

void silence_errors() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

Handle open_file_readonly(const std::string& path, External external) {
  silence_errors();
  require_regular_file(path, "file");
  htri_t is_h5 = H5Fis_hdf5(path.c_str());
  if (is_h5 < 0) throw IoError(path + ": cannot be read");
  if (is_h5 == 0) throw FormatError(path + ": not an HDF5 file (no HDF5 signature)");
  hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) throw FormatError(path + ": HDF5 file cannot be opened (truncated or corrupt?)");
  Handle file(f);
  ++g_files_opened;
  check_external(file.get(), path, external);
  return file;
}

bool exists(hid_t loc, const std::string& name) {
  // Walk the path one component at a time: H5Lexists fails on a missing intermediate group.
  std::string partial;
  std::size_t pos = 0;
  if (!name.empty() && name[0] == '/') {
    partial = "/";
    pos = 1;
  }
  while (pos <= name.size()) {
    std::size_t next = name.find('/', pos);
    std::string comp = name.substr(pos, next == std::string::npos ? std::string::npos : next - pos);
    if (!comp.empty()) {
      partial += (partial.empty() || partial.back() == '/') ? comp : "/" + comp;
      if (H5Lexists(loc, partial.c_str(), H5P_DEFAULT) <= 0) return false;
      if (H5Oexists_by_name(loc, partial.c_str(), H5P_DEFAULT) <= 0) return false;
    }
    if (next == std::string::npos) break;
    pos = next + 1;
  }
  return true;
}

std::vector<hsize_t> dataset_shape(hid_t dataset) {
  Handle space(H5Dget_space(dataset));
  int rank = H5Sget_simple_extent_ndims(space.get());
  std::vector<hsize_t> dims(rank > 0 ? rank : 0);
  if (rank > 0) H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  return dims;
}

std::vector<std::string> group_members(hid_t group) {
  std::vector<std::string> names;
  H5G_info_t info;
  if (H5Gget_info(group, &info) < 0) return names;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    ssize_t len = H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    if (len < 0) continue;
    std::string s(std::size_t(len) + 1, '\0');
    H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, s.data(), s.size(), H5P_DEFAULT);
    s.resize(std::size_t(len));
    names.push_back(std::move(s));
  }
  return names;
}

std::vector<std::string> datasets_in(hid_t loc, const std::string& group) {
  std::vector<std::string> names;
  if (!exists(loc, group)) return names;
  Handle g(H5Gopen2(loc, group.c_str(), H5P_DEFAULT));
  if (!g) return names;
  for (const std::string& n : group_members(g.get())) {
    Handle obj(H5Oopen(g.get(), n.c_str(), H5P_DEFAULT));
    if (obj && H5Iget_type(obj.get()) == H5I_DATASET) names.push_back(n);
  }
  return names;
}

}  // namespace tsp::h5
