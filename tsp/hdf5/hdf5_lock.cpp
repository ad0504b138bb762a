#include "tsp/hdf5/hdf5_lock.h"

namespace tsp {
std::mutex& hdf5_mutex() {
  static std::mutex m;
  return m;
}
}  // namespace tsp
