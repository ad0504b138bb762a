// One process-wide lock for HDF5: Debian's libhdf5 is built without thread safety, so every
// thread that calls the HDF5 C API must hold this mutex (the .tsp reader and writer do).
#pragma once
#include <mutex>

namespace tsp {

/// The mutex serializing all HDF5 calls in the process (not recursive); never throws.
std::mutex& hdf5_mutex();

}  // namespace tsp
