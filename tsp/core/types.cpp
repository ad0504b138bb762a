#include "tsp/core/types.h"

#include "tsp/core/error.h"

namespace tsp {

std::string to_string(const Dims& d) {
  return std::to_string(d.x) + "x" + std::to_string(d.y) + "x" + std::to_string(d.z);
}

void check_grid(std::int64_t x, std::int64_t y, std::int64_t z, std::int64_t steps,
                const std::string& where) {
  auto grid = [&] { return std::to_string(x) + "x" + std::to_string(y) + "x" + std::to_string(z); };
  for (std::int64_t e : {x, y, z})
    if (e < 1 || e > kMaxGridEdge)
      throw FormatError(where + ": grid " + grid() + ", expected every edge in [1, " +
                        std::to_string(kMaxGridEdge) + "] samples");
  if (x * y * z > kMaxStepSamples)  // each ≤ 2^16: no overflow
    throw FormatError(where + ": grid " + grid() + " holds " + std::to_string(x * y * z) +
                      " samples per step, expected at most " + std::to_string(kMaxStepSamples));
  if (steps < 1 || steps > kMaxSteps)
    throw FormatError(where + ": " + std::to_string(steps) + " time steps, expected 1 to " +
                      std::to_string(kMaxSteps));
}

}  // namespace tsp
