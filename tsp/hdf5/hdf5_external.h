// What an HDF5 file may read outside itself: external links (a group or dataset in another
// file), external raw storage (a dataset's bytes in other files, H5Pset_external) and virtual
// datasets (mapped from other datasets, possibly in other files). A file a user names could
// point these at any file the user can read (/etc/passwd, a FIFO, /dev/zero), so they are
// refused unless the user allows them (`--allow-external`).
#pragma once
#include <hdf5.h>

#include <string>

namespace tsp::h5 {

/// Whether an opened file may read other files.
enum class External {
  refuse,  ///< any external link, external storage or virtual dataset is an error
  allow,   ///< allowed, but every other file it names that exists must be a regular file
};

/// Visits every link and dataset of file (opened from path): with External::refuse, throws
/// UsageError naming path, the object and the other file at the first external link,
/// user-defined link, dataset with external storage or virtual dataset; with External::allow,
/// throws IoError when such an object names an existing file that is not a regular file (a
/// FIFO or a device would block or never end). Never follows a link outside the file. The
/// caller holds the HDF5 lock (hdf5_lock.h) where threads share HDF5.
void check_external(hid_t file, const std::string& path, External policy);

}  // namespace tsp::h5
