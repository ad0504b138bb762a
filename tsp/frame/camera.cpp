#include "tsp/frame/camera.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdlib>
#include <glm/gtc/matrix_transform.hpp>
#include <string>

#include "tsp/core/error.h"

namespace tsp {

namespace {
constexpr double kPi = 3.14159265358979323846;
double radians(double deg) { return deg * kPi / 180.0; }
// A placed eye's near plane, as a share of the frame's bounding radius.
constexpr double kPlacedEyeNear = 1e-3;
}  // namespace

Camera::Camera(Dims dims, const CameraParams& p) : params_(p) {
  assert(p.width > 0 && p.height > 0 && p.zoom > 0);
  assert(p.voxel_size[0] > 0 && p.voxel_size[1] > 0 && p.voxel_size[2] > 0);
  // World = sample coordinates stretched by the voxel size, smallest axis 1.
  const double smallest = std::min({p.voxel_size[0], p.voxel_size[1], p.voxel_size[2]});
  const glm::dvec3 stretch(p.voxel_size[0] / smallest, p.voxel_size[1] / smallest,
                           p.voxel_size[2] / smallest);
  // World of sample s = origin / smallest + stretch · s; the view fits the frame (or the volume).
  const glm::dvec3 shift =
      glm::dvec3(p.origin[0], p.origin[1], p.origin[2]) / smallest;
  glm::dvec3 lo = shift;
  glm::dvec3 hi = shift + stretch * glm::dvec3(std::max(dims.x - 1, 0), std::max(dims.y - 1, 0),
                                               std::max(dims.z - 1, 0));
  if (!is_empty(p.frame)) {
    lo = glm::dvec3(p.frame.lo[0], p.frame.lo[1], p.frame.lo[2]) / smallest;
    hi = glm::dvec3(p.frame.hi[0], p.frame.hi[1], p.frame.hi[2]) / smallest;
  }
  const glm::dvec3 centre = (lo + hi) * 0.5;
  // Bounding-sphere radius; a single-voxel volume still gets a unit sphere.
  const double radius = std::max(0.5 * glm::length(hi - lo), 0.5);
  const double az = radians(p.azimuth_deg), el = radians(p.elevation_deg);
  const glm::dvec3 to_eye(std::cos(el) * std::sin(az), -std::cos(el) * std::cos(az), std::sin(el));
  const glm::dvec3 up_hint(0, 0, 1);
  // Right and up of the image plane; elevation stays inside (−90°, 90°) so up_hint is never parallel.
  const glm::dvec3 right = glm::normalize(glm::cross(-to_eye, up_hint));
  const glm::dvec3 up = glm::cross(right, -to_eye);
  const glm::dvec3 target = centre + radius * (p.pan[0] * right + p.pan[1] * up);
  const double aspect = double(p.width) / double(p.height);
  double distance;
  if (p.projection == Projection::perspective) {
    const double half_fov = radians(p.fov_deg) * 0.5;
    // Fits the sphere in the smaller of the two fields of view.
    const double half = std::min(half_fov, std::atan(std::tan(half_fov) * aspect));
    distance = radius / std::sin(half) / p.zoom;
    const double near_plane = std::max(distance - radius * 1.01, radius * 1e-3);
    projection_ = glm::perspective(radians(p.fov_deg), aspect, near_plane, distance + radius * 1.01);
  } else {
    distance = radius * 3;
    const double half_h = radius / p.zoom * (aspect < 1 ? 1 / aspect : 1);
    const double half_w = half_h * aspect;
    projection_ = glm::ortho(-half_w, half_w, -half_h, half_h, distance - radius * 1.01,
                             distance + radius * 1.01);
  }
  glm::dvec3 eye_world = target + to_eye * distance;
  glm::dvec3 look_at = target;
  if (p.projection == Projection::perspective && p.eye) {
    // A placed eye: near plane close to it, far plane beyond the frame's farthest corner.
    eye_world = shift + stretch * glm::dvec3((*p.eye)[0], (*p.eye)[1], (*p.eye)[2]);
    look_at = eye_world - to_eye;
    double farthest = 0;
    for (int c = 0; c < 8; ++c)
      farthest = std::max(farthest, glm::length(glm::dvec3(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y,
                                                           c & 4 ? hi.z : lo.z) -
                                                eye_world));
    projection_ = glm::perspective(radians(p.fov_deg), aspect, radius * kPlacedEyeNear,
                                   std::max(farthest, radius) * 1.01);
  }
  // Back to sample coordinates: points divide by the stretch; depth = dot(−to_eye, stretch·x),
  // so the planes of equal depth have normal stretch·(−to_eye); rays run along (−to_eye)/stretch.
  eye_ = (eye_world - shift) / stretch;
  dir_ = glm::normalize(-to_eye * stretch);
  ray_ = glm::normalize(-to_eye / stretch);
  ray_cosine_ = std::clamp(glm::dot(ray_, dir_), 1e-6, 1.0);
  view_ = glm::lookAt(eye_world, look_at, up) * glm::translate(glm::dmat4(1.0), shift) *
          glm::scale(glm::dmat4(1.0), stretch);
}

std::array<double, 2> parse_view_angles(const std::string& text) {
  auto comma = text.find(',');
  auto number = [&](const std::string& s) {
    char* end = nullptr;
    double v = std::strtod(s.c_str(), &end);
    if (s.empty() || end != s.c_str() + s.size() || !std::isfinite(v))
      throw UsageError("--view '" + text + "': expected AZ,EL in degrees, e.g. 30,20");
    return v;
  };
  if (comma == std::string::npos)
    throw UsageError("--view '" + text + "': expected AZ,EL in degrees, e.g. 30,20");
  double az = number(text.substr(0, comma)), el = number(text.substr(comma + 1));
  if (el <= -90 || el >= 90)
    throw UsageError("--view '" + text + "': elevation must lie strictly between -90 and 90");
  return {az, el};
}

ScreenFootprint screen_footprint(const Camera& camera, const Aabb& box) {
  ScreenFootprint f;
  const glm::dmat4 vp = camera.view_projection();
  const double w = camera.params().width, h = camera.params().height;
  std::array<int, 6> outside{};  // corners beyond each clip plane
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (int c = 0; c < 8; ++c) {
    const glm::dvec4 q = vp * glm::dvec4(c & 1 ? box.hi[0] : box.lo[0],
                                          c & 2 ? box.hi[1] : box.lo[1],
                                          c & 4 ? box.hi[2] : box.lo[2], 1.0);
    outside[0] += q.x < -q.w;
    outside[1] += q.x > q.w;
    outside[2] += q.y < -q.w;
    outside[3] += q.y > q.w;
    outside[4] += q.z < -q.w;
    outside[5] += q.z > q.w;
    if (q.w <= 1e-9) {
      f.behind = true;
      continue;
    }
    const double sx = (q.x / q.w * 0.5 + 0.5) * w, sy = (q.y / q.w * 0.5 + 0.5) * h;
    x0 = std::min(x0, sx);
    x1 = std::max(x1, sx);
    y0 = std::min(y0, sy);
    y1 = std::max(y1, sy);
  }
  for (int n : outside) f.culled |= n == 8;
  f.rect = f.behind ? std::array<double, 4>{0, 0, w, h} : std::array<double, 4>{x0, y0, x1, y1};
  return f;
}

}  // namespace tsp
