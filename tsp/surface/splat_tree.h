// TetSplat's splat hierarchy over a mesh's boundary (seed paper 001 §3): each boundary triangle
// is a leaf splat — a disc at its centroid, in its plane, holding its corners — and each inner
// node one splat standing for its two children (area-weighted centre, normal and field value,
// a radius holding theirs). A cut by a minimum splat size in pixels is what a frame draws:
// larger minimum, fewer and larger splats, a faster frame.
#pragma once
#include <array>
#include <vector>

#include "tsp/core/types.h"
#include "tsp/frame/camera.h"
#include "tsp/source/mesh_source.h"
#include "tsp/surface/boundary.h"

namespace tsp {

/// One splat, in sample coordinates (the volume's voxels: (p − origin) / spacing).
struct SurfaceSplat {
  std::array<float, 3> centre{};
  std::array<float, 3> normal{0, 0, 1};  ///< unit, outwards (area-weighted mean below a leaf)
  float radius = 0;                      ///< holds the splats (or the triangle) it stands for
  float area = 0;                        ///< of the triangles it stands for
  float value = 0;                       ///< the field, area-weighted over them
};

/// A node of the hierarchy: its splat and its two children (−1, −1 for a leaf). A leaf also
/// keeps its triangle, which is drawn instead of its disc (the boundary itself, exactly).
struct SplatTreeNode {
  SurfaceSplat splat;
  std::array<int, 2> child{-1, -1};
  std::array<std::array<float, 3>, 3> triangle{};  ///< a leaf's corners (sample coordinates)
  bool is_leaf() const { return child[0] < 0; }
};

/// The hierarchy: nodes in pre-order (the root first, a node before its children).
struct SplatTree {
  std::vector<SplatTreeNode> nodes;
  int leaves = 0;            ///< leaf splats (boundary triangles of non-zero area)
  ValueRange value_range;    ///< of the leaves' values
};

/// Builds the hierarchy over boundary (of mesh, whose values are the field drawn on it: a
/// triangle takes the mean of its corners' point values, or its cell's value), points mapped
/// to sample coordinates by (p − origin) / spacing (spacing > 0). Splits at the median along
/// the longest axis of the centres. Degenerate triangles are left out. Never throws (but
/// bad_alloc).
SplatTree build_splat_tree(const Mesh& mesh, const BoundaryTriangles& boundary,
                           const std::array<double, 3>& origin,
                           const std::array<double, 3>& spacing);

/// The projected diameter in pixels of splat s through camera (perspective: at its depth; 0
/// behind the eye). Never throws.
double projected_diameter(const Camera& camera, const SurfaceSplat& s);

/// The cut for a minimum splat size of min_px pixels: from the root down, a node is drawn when
/// it is a leaf or its projected diameter is at most min_px, else its children are visited.
/// min_px ≤ 0: every leaf. Node ids in pre-order. Never throws.
std::vector<int> splat_surface_cut(const SplatTree& tree, const Camera& camera, double min_px);

}  // namespace tsp
