// tsp/hdf5: the HDF5 plumbing the readers and the .tsp file share (handles, lock, typed values);
// may include core/.
// Minimal RAII and error plumbing over the HDF5 C API, shared by the readers and the .tsp file.
#pragma once
#include <hdf5.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "tsp/hdf5/hdf5_external.h"

namespace tsp::h5 {

/// Owns one HDF5 identifier (file, group, dataset, dataspace, type, property list, attribute).
class Handle {
 public:
  Handle() = default;
  /// Takes ownership of id; a negative id is kept as "invalid".
  explicit Handle(hid_t id) : id_(id) {}
  Handle(Handle&& o) noexcept : id_(std::exchange(o.id_, H5I_INVALID_HID)) {}
  Handle& operator=(Handle&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, H5I_INVALID_HID);
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { reset(); }
  /// The raw identifier.
  hid_t get() const { return id_; }
  /// True when the identifier is valid.
  explicit operator bool() const { return id_ >= 0; }
  /// Closes the identifier now.
  void reset();
  /// Gives up ownership: returns the identifier, which the caller must close. Never throws.
  hid_t release() { return std::exchange(id_, H5I_INVALID_HID); }

 private:
  hid_t id_ = H5I_INVALID_HID;
};

/// Turns off HDF5's automatic error stack printing (errors become our exceptions); idempotent.
void silence_errors();

/// Names of the datasets directly in group (empty when the group is absent). Never throws.
std::vector<std::string> datasets_in(hid_t loc, const std::string& group);

/// Opens an existing regular file read-only and checks what it reads outside itself
/// (check_external with external); throws IoError (missing, not a regular file, unreadable),
/// FormatError (not HDF5) or UsageError (refused external links or storage).
Handle open_file_readonly(const std::string& path, External external = External::refuse);

/// Number of files open_file_readonly has opened in this process (each open also walks the
/// file for external links and storage: tests count them). Never throws.
std::int64_t files_opened();

/// True when `name` (an absolute or relative path like "/a/b") exists below loc, all links resolved.
bool exists(hid_t loc, const std::string& name);

/// Dimensions of a dataset's dataspace (outermost first, as HDF5 lists them).
std::vector<hsize_t> dataset_shape(hid_t dataset);

/// Names of the direct members of a group, in HDF5's index (name) order.
std::vector<std::string> group_members(hid_t group);

}  // namespace tsp::h5
