// The view of the volume: an orbit camera given as azimuth/elevation around the volume's centre,
// orthographic or perspective. Pure math (GLM), shared by the renderer, slicing and ordering.
#pragma once
#include <array>
#include <optional>
#include <glm/glm.hpp>

#include "tsp/core/geometry.h"
#include "tsp/core/types.h"

namespace tsp {

/// Projection kind.
enum class Projection { orthographic, perspective };

/// What the user chooses: angles in degrees, zoom (1 = the whole volume fits), viewport size.
struct CameraParams {
  double azimuth_deg = 30;    ///< around +z; 0 looks from −y towards +y (x right, z up)
  double elevation_deg = 20;  ///< above the x-y plane, in (−90, 90)
  double zoom = 1;            ///< > 0; 2 shows half the width
  Projection projection = Projection::orthographic;
  double fov_deg = 30;        ///< vertical field of view for perspective
  std::array<double, 2> pan{0, 0};  ///< shift of the look-at point, in units of the bounding radius
  int width = 640, height = 480;
  /// Physical size of a voxel per axis (any positive scale): the volume is shown in these
  /// proportions (the .tsp's spacing, times any exaggeration). {1, 1, 1}: sample proportions.
  std::array<double, 3> voxel_size{1, 1, 1};
  /// Where sample (0, 0, 0) lies, in the units of voxel_size: with `frame`, places this volume
  /// among the file's other fields (a staggered field sits half a cell off).
  std::array<double, 3> origin{0, 0, 0};
  /// The box the view fits and turns around, in the units of voxel_size (the file's fields
  /// united, so that switching fields keeps the view); empty (lo > hi): the volume's own box.
  Aabb frame = empty_aabb();
  /// Perspective only: the eye placed here (sample coordinates, voxels; inside the volume or
  /// out), looking along the direction the angles give (towards the centre from azimuth and
  /// elevation), instead of orbiting at the distance that fits the frame; zoom and pan are not
  /// used then. Empty: the orbit camera.
  std::optional<std::array<double, 3>> eye;
  bool operator==(const CameraParams&) const = default;
};

/// A camera fitted to a volume's geometry [0, D−1]³ in sample coordinates. With anisotropic
/// voxels (CameraParams::voxel_size) the world is the sample grid stretched by the voxel size
/// (normalised so its smallest axis is 1): view() maps sample coordinates through that stretch,
/// and in sample coordinates the slice planes' normal (direction()) and the orthographic rays
/// (ray_direction()) differ.
class Camera {
 public:
  /// Fits the view to dims; asserts width, height > 0, zoom > 0 and a positive voxel size.
  Camera(Dims dims, const CameraParams& params);
  /// Sample coordinates → eye space.
  const glm::dmat4& view() const { return view_; }
  /// Eye space → clip space.
  const glm::dmat4& projection() const { return projection_; }
  /// projection · view.
  glm::dmat4 view_projection() const { return projection_ * view_; }
  /// Eye position in sample coordinates.
  std::array<double, 3> eye() const { return {eye_.x, eye_.y, eye_.z}; }
  /// Unit normal of the planes of equal depth (view-aligned slices), pointing from the eye into
  /// the scene, in sample coordinates: the view direction when voxels are cubes.
  std::array<double, 3> direction() const { return {dir_.x, dir_.y, dir_.z}; }
  /// Unit direction of the orthographic rays (perspective: of the central ray) from the eye
  /// into the scene, in sample coordinates; direction() when voxels are cubes.
  std::array<double, 3> ray_direction() const { return {ray_.x, ray_.y, ray_.z}; }
  /// dot(ray_direction(), direction()) in (0, 1] (1 for cubic voxels): slice planes lie
  /// spacing × ray_cosine() apart along direction(), so that samples lie `spacing` sample units
  /// apart along the rays, however stretched the voxels.
  double ray_cosine() const { return ray_cosine_; }
  /// True for perspective projection.
  bool perspective() const { return params_.projection == Projection::perspective; }
  /// The parameters it was made from.
  const CameraParams& params() const { return params_; }

 private:
  CameraParams params_;
  glm::dmat4 view_{1.0}, projection_{1.0};
  glm::dvec3 eye_{0.0}, dir_{0.0, 1.0, 0.0}, ray_{0.0, 1.0, 0.0};
  double ray_cosine_ = 1;
};

/// Where a box lands on the image.
struct ScreenFootprint {
  std::array<double, 4> rect{};  ///< x0, y0, x1, y1 in pixels, unclipped (y up, as GL's window)
  bool behind = false;           ///< a corner lies behind the eye: rect is the whole image
  bool culled = false;           ///< all eight corners beyond one clip plane (outside the frustum)
};

/// The bounding rectangle of box's projected corners (sample coordinates) through camera, and
/// whether the box lies wholly outside the view frustum. Never throws.
ScreenFootprint screen_footprint(const Camera& camera, const Aabb& box);

/// Parses "AZ,EL" in degrees; throws UsageError naming the option text.
std::array<double, 2> parse_view_angles(const std::string& text);

}  // namespace tsp
