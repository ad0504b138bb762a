// The LOD error of a cut node (spec §14): its largest texel's projected size in pixels (paper 000
// §5.1) times its colour error at its level under the current TF — the level's RMS residual
// (data units, stored per node and step) times the TF's steepest colour change over the node's
// value range (ΔE*uv per data unit) — weighted by distance to the focus point (paper 002's
// centre of attention). Uniform nodes (residual 0) and transparent ones (slope 0) cost nothing.
#pragma once
#include <algorithm>
#include <array>
#include <optional>
#include <vector>

#include "tsp/core/color.h"
#include "tsp/core/geometry.h"
#include "tsp/frame/camera.h"
#include "tsp/metric/transfer_function.h"
#include "tsp/tree/tsp_tree.h"

namespace tsp {

/// Per-entry colours of a TF as seen (premultiplied over black, in L*u*v*), for slopes over value
/// ranges. Immutable after construction; safe to share between threads.
class TfColourSlopes {
 public:
  /// Tabulates tf. Never throws.
  explicit TfColourSlopes(const TransferFunction& tf);
  /// Largest ΔE*uv per data unit between neighbouring entries over [lo, hi] plus one entry on each
  /// side; 0 when all of them are transparent.
  double slope(double lo, double hi) const;
  /// True when every entry over [lo, hi] has α = 0.
  bool transparent(double lo, double hi) const;

 private:
  const TransferFunction* tf_;
  std::vector<double> step_;  // ΔE between entry j and j + 1, per data unit
};

/// Where a node's box lands on screen.
struct NodeProjection {
  bool culled = false;           ///< wholly outside the view frustum
  double pixels_per_voxel = 0;   ///< at the box point nearest the eye (the centre, orthographic)
  double pixel_area = 0;         ///< its screen bounding rectangle, clipped to the viewport
  double depth_voxels = 0;       ///< its extent along the view direction
  std::array<double, 4> rect{};  ///< screen bounding rectangle x0, y0, x1, y1 (pixels, clipped)
};

/// Projects box (sample coordinates) through camera. Never throws.
NodeProjection project_box(const Camera& camera, const Aabb& box);
/// project_box of every octree node's geometric box, indexed by node. Never throws.
std::vector<NodeProjection> project_nodes(const Octree& octree, const Camera& camera);

/// Focus weight of a node centred at c: 1 / (1 + 2·|c − focus| / diagonal), paper 002's distance
/// falloff from the centre of attention (diagonal: the volume's). Never throws.
double focus_weight(const std::array<double, 3>& c, const std::array<double, 3>& focus,
                    double diagonal);

/// How much of each leaf brick the frame shows: the transmittance in front of it (mean over its
/// screen tiles), from every leaf's opacity under the TF (the mean α per voxel over its values'
/// mean ± σ, over its mean chord) accumulated front to back on a coarse tile grid — occlusion, so that what lies
/// behind opaque matter stays coarse. leaves: project_box of each leaf brick. Indexed by leaf
/// brick. Never throws.
std::vector<double> leaf_visibility(const TspTree& tree, int t, const Camera& camera,
                                    const std::vector<NodeProjection>& leaves,
                                    const TransferFunction& tf);

/// Field-of-view weight of a node (paper 002): 1 / (1 + r), r = the distance of its screen
/// rectangle's centre from the image centre over half the image diagonal — the periphery of the
/// view matters less than its middle. Never throws.
double view_weight(const NodeProjection& p, const Camera& camera);

/// The LOD error of octree node o at step t (0 for a leaf or a culled node). Never throws.
double lod_error(const TspTree& tree, int o, int t, const NodeProjection& p,
                 const TfColourSlopes& slopes, double weight);

}  // namespace tsp
