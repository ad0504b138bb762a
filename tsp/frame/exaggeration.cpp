#include "tsp/frame/exaggeration.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace tsp {

std::array<double, 3> vertical_exaggeration(const Aabb& frame) {
  if (is_empty(frame)) return {1, 1, 1};
  const double width = std::max(frame.hi[0] - frame.lo[0], frame.hi[1] - frame.lo[1]);
  const double height = frame.hi[2] - frame.lo[2];
  // Flat: low against the larger horizontal edge, and lower than the smaller one too (a bar,
  // long in x and as thin in y as in z, is not a flat domain).
  const double narrow = std::min(frame.hi[0] - frame.lo[0], frame.hi[1] - frame.lo[1]);
  if (!(height > 0) || !std::isfinite(width) || !(height < kFlatAspect * width) ||
      !(height < narrow))
    return {1, 1, 1};
  const double want = width / height / 3;
  // The round number nearest `want` on a log scale.
  double best = 1;
  for (double decade = 1; decade <= kMaxAutoExaggeration; decade *= 10)
    for (double m : {1.0, 2.0, 3.0, 5.0}) {
      const double k = m * decade;
      if (k > kMaxAutoExaggeration) break;
      if (std::fabs(std::log(k / want)) < std::fabs(std::log(best / want))) best = k;
    }
  return {1, 1, best};
}

std::string exaggeration_text(const std::array<double, 3>& scale, bool ascii) {
  std::string text;
  const char* names[3] = {"x", "y", "z"};
  for (std::size_t a = 0; a < 3; ++a) {
    if (scale[a] == 1) continue;
    char k[32];
    std::snprintf(k, sizeof k, "%g", scale[a]);
    text += (text.empty() ? "" : ", ") + std::string(names[a]) + (ascii ? " x " : " × ") + k;
  }
  return text;
}

}  // namespace tsp
