#include "tsp/frame/slicing.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "tsp/core/error.h"

namespace tsp {
namespace {

constexpr double kUnitTolerance = 1e-9;

std::string vec_str(const std::array<double, 3>& v) {
  return "(" + std::to_string(v[0]) + ", " + std::to_string(v[1]) + ", " + std::to_string(v[2]) +
         ")";
}

}  // namespace

SlicePlanes SlicePlanes::toward(std::array<double, 3> dir, double spacing) {
  const double len = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
  if (!std::isfinite(len) || len == 0)
    throw UsageError("slice planes: view direction must be finite and non-zero, found " +
                     vec_str(dir));
  SlicePlanes p;
  for (int a = 0; a < 3; ++a) p.dir[a] = dir[a] / len;
  p.spacing = spacing;
  validate(p);
  return p;
}

void validate(const SlicePlanes& planes) {
  const auto& d = planes.dir;
  const double len2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  if (!std::isfinite(len2) || std::abs(len2 - 1.0) > kUnitTolerance)
    throw UsageError("slice planes: view direction must be a unit vector, found " + vec_str(d));
  if (!std::isfinite(planes.spacing) || !(planes.spacing > 0))
    throw UsageError("slice planes: spacing must be positive and finite, found " +
                     std::to_string(planes.spacing));
}

}  // namespace tsp
