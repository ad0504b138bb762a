#include "tsp/hdf5/hdf5_external.h"

#include <filesystem>
#include <vector>

#include "tsp/core/error.h"
#include "tsp/core/file_check.h"
#include "tsp/hdf5/hdf5_handle.h"

namespace tsp::h5 {
namespace {

namespace fs = std::filesystem;

const char* const kAllowHint = "; it reads outside the input: pass --allow-external to allow it";

struct Visit {
  std::string path;  // the file being checked
  External policy;
  std::string error;  // set by the callback, thrown by check_external (never through HDF5)
  bool usage = false;
};

// Every place HDF5 may look for a file named `name` from the file at `path`: as given (relative
// to the working directory) and beside the file. Each that exists must be a regular file.
void require_regular_targets(const std::string& path, const std::string& name,
                             const std::string& what) {
  std::vector<fs::path> candidates{fs::path(name)};
  if (fs::path(name).is_relative()) candidates.push_back(fs::path(path).parent_path() / name);
  for (const fs::path& c : candidates) {
    std::error_code ec;
    if (!fs::exists(c, ec)) continue;
    try {
      require_regular_file(c.string(), "file");
    } catch (const IoError& e) {
      throw IoError(path + ", " + what + ": " + e.what());
    }
  }
}

// A dataset's external storage and virtual sources.
void check_dataset(hid_t dataset, const std::string& name, Visit& v) {
  Handle dcpl(H5Dget_create_plist(dataset));
  if (!dcpl) return;
  if (H5Pget_layout(dcpl.get()) == H5D_VIRTUAL) {
    std::size_t count = 0;
    H5Pget_virtual_count(dcpl.get(), &count);
    for (std::size_t i = 0; i < count; ++i) {
      const ssize_t len = H5Pget_virtual_filename(dcpl.get(), i, nullptr, 0);
      std::string file(std::size_t(std::max<ssize_t>(len, 0)) + 1, '\0');
      if (len > 0) H5Pget_virtual_filename(dcpl.get(), i, file.data(), file.size());
      file.resize(std::size_t(std::max<ssize_t>(len, 0)));
      if (v.policy == External::refuse) {
        v.usage = true;
        v.error = v.path + ", dataset /" + name + ": a virtual dataset mapped from \"" + file +
                  "\"" + kAllowHint;
        return;
      }
      if (file != ".") require_regular_targets(v.path, file, "dataset /" + name + " (virtual)");
    }
    return;
  }
  const int count = H5Pget_external_count(dcpl.get());
  for (int i = 0; i < count; ++i) {
    char file[4096] = {};
    off_t offset = 0;
    hsize_t size = 0;
    if (H5Pget_external(dcpl.get(), unsigned(i), sizeof file - 1, file, &offset, &size) < 0)
      file[0] = '\0';
    if (v.policy == External::refuse) {
      v.usage = true;
      v.error = v.path + ", dataset /" + name + ": raw data stored in the external file \"" +
                file + "\"" + kAllowHint;
      return;
    }
    require_regular_targets(v.path, file, "dataset /" + name + " (external storage)");
  }
}

herr_t visit_link(hid_t group, const char* name, const H5L_info_t* info, void* data) {
  Visit& v = *static_cast<Visit*>(data);
  try {
    if (info->type == H5L_TYPE_HARD) {
      Handle obj(H5Oopen(group, name, H5P_DEFAULT));
      if (obj && H5Iget_type(obj.get()) == H5I_DATASET) check_dataset(obj.get(), name, v);
    } else if (info->type >= H5L_TYPE_UD_MIN) {
      std::string target = "another file";
      if (info->type == H5L_TYPE_EXTERNAL) {
        std::vector<char> buf(info->u.val_size + 1, '\0');
        const char *file = nullptr, *object = nullptr;
        unsigned flags = 0;
        if (H5Lget_val(group, name, buf.data(), buf.size(), H5P_DEFAULT) >= 0 &&
            H5Lunpack_elink_val(buf.data(), info->u.val_size, &flags, &file, &object) >= 0 &&
            file) {
          target = std::string(file) + ":" + (object ? object : "");
          if (v.policy == External::allow)
            require_regular_targets(v.path, file, "external link /" + std::string(name));
        }
      }
      if (v.policy == External::refuse) {
        v.usage = true;
        v.error = v.path + ": /" + name + " is " +
                  (info->type == H5L_TYPE_EXTERNAL ? "an external link to " + target
                                                   : std::string("a user-defined link")) +
                  kAllowHint;
      }
    }
  } catch (const Error& e) {
    v.error = e.what();
  }
  return v.error.empty() ? 0 : 1;  // a positive value stops the visit
}

}  // namespace

void check_external(hid_t file, const std::string& path, External policy) {
  Visit v{path, policy, {}, false};
  if (H5Lvisit(file, H5_INDEX_NAME, H5_ITER_INC, visit_link, &v) < 0 && v.error.empty())
    throw FormatError(path + ": the file's links cannot be listed (truncated or corrupt?)");
  if (v.error.empty()) return;
  if (v.usage) throw UsageError(v.error);
  throw IoError(v.error);
}

}  // namespace tsp::h5
