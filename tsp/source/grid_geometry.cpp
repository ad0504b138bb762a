#include "tsp/source/grid_geometry.h"

#include <cmath>

#include "tsp/core/error.h"

namespace tsp::io {

GridGeometry image_geometry(const std::optional<std::vector<double>>& origin,
                            const std::optional<std::vector<double>>& spacing, bool cells,
                            const std::string& where) {
  GridGeometry g;
  auto take = [&](const std::optional<std::vector<double>>& v, std::array<double, 3>& out,
                  const char* name, bool positive) {
    if (!v) return;
    if (v->size() != 3)
      throw FormatError(where + ": " + name + " has " + std::to_string(v->size()) +
                        " values, expected 3");
    for (int a = 0; a < 3; ++a) {
      const double x = (*v)[std::size_t(a)];
      if (!std::isfinite(x) || (positive && !(x > 0)))
        throw FormatError(where + ": " + name + " " + std::to_string(x) + " on axis " +
                          std::to_string(a) + ", expected a finite" +
                          (positive ? " positive" : "") + " number");
      out[std::size_t(a)] = x;
    }
  };
  take(origin, g.origin, "Origin", false);
  take(spacing, g.spacing, "Spacing", true);
  if (cells)
    for (int a = 0; a < 3; ++a) g.origin[std::size_t(a)] += 0.5 * g.spacing[std::size_t(a)];
  return g;
}

}  // namespace tsp::io
