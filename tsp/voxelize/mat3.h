// 3 × 3 determinants and inverses, for barycentric and parametric coordinates in the voxelizer.
#pragma once
#include <cmath>

namespace tsp::detail {

/// Determinant of m (row-major). Never throws.
inline double det3(const double m[3][3]) {
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
         m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

/// The inverse of m into r when |det m| > min_abs_det (false, r untouched, otherwise). Never
/// throws.
inline bool inverse3(const double m[3][3], double r[3][3], double min_abs_det) {
  const double det = det3(m);
  if (!(std::fabs(det) > min_abs_det)) return false;
  const double inv = 1.0 / det;
  r[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) * inv;
  r[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) * inv;
  r[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) * inv;
  r[1][0] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) * inv;
  r[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) * inv;
  r[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) * inv;
  r[2][0] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) * inv;
  r[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) * inv;
  r[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) * inv;
  return true;
}

}  // namespace tsp::detail
