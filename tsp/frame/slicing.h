// View-aligned slicing of boxes (spec §7): the box, the slice planes shared by every box, and
// the polygon list both slicers (slicer.h, naive_slicer.h) append to. Pure geometry in
// sample coordinates (sample i of an axis sits at coordinate i).
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "tsp/core/geometry.h"

namespace tsp {

/// Planes perpendicular to the view: plane k is dot(p, dir) = (k + ½)·spacing for every integer
/// k, the same planes for every box, so neighbouring boxes' polygons meet exactly. The half
/// offset keeps planes off integer-coordinate corners in axis-aligned views. Larger dot(p, dir)
/// is farther from the eye.
struct SlicePlanes {
  std::array<double, 3> dir{0, 0, 1};  ///< unit vector from the eye into the scene
  double spacing = 0.5;                ///< distance between planes, in voxels

  /// Planes along dir normalized; throws UsageError when dir is zero or not finite, or when
  /// spacing is not positive and finite.
  static SlicePlanes toward(std::array<double, 3> dir, double spacing);
  /// Distance of plane k from the origin along dir.
  double depth(std::int64_t k) const { return (double(k) + 0.5) * spacing; }
};

/// Throws UsageError unless dir is a finite unit vector (within 1e-9) and spacing is positive
/// and finite; both slicers call it.
void validate(const SlicePlanes& planes);

/// Convex slice polygons, appended box after box, slice after slice. Coordinates are double so
/// callers can compare slicers exactly; the renderer converts while it adds texture coordinates.
/// clear() keeps the capacity, so one soup reused across boxes and frames stops allocating.
struct PolygonSoup {
  std::vector<double> xyz;           ///< x, y, z of each vertex, polygon after polygon
  std::vector<int> counts;           ///< vertices of each polygon, 3 to 6
  std::vector<std::int64_t> planes;  ///< plane index k of each polygon

  /// Removes every polygon, keeping the memory.
  void clear() {
    xyz.clear();
    counts.clear();
    planes.clear();
  }
  /// Number of polygons.
  std::size_t size() const { return counts.size(); }
  /// Number of vertices of all polygons.
  std::size_t vertex_count() const { return xyz.size() / 3; }
};

}  // namespace tsp
