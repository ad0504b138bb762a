#include "tsp/core/types.h"

namespace tsp {
std::string to_string(const Dims& d) {
  return std::to_string(d.x) + "x" + std::to_string(d.y) + "x" + std::to_string(d.z);
}
}  // namespace tsp
