// tsp/clip: CSG probes that clip the volume (paper 001, TetSplat): planes, spheres and oriented
// boxes in physical coordinates, combined by intersection, union or subtraction; layered over the
// tree (a per-node classification the traversal and the LOD cut read), not folded into it. May
// include core/ and tree/.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "tsp/core/geometry.h"
#include "tsp/tree/marks.h"
#include "tsp/tree/octree.h"

namespace tsp {

/// One probe: a solid in physical coordinates.
struct Probe {
  enum class Kind : std::uint8_t { plane, sphere, box };
  Kind kind = Kind::plane;
  /// plane: unit normal (a, b, c) and offset d, the solid {p : n·p ≤ d};
  /// sphere: centre and radius in [3]; box: centre, then half sizes in `size`.
  std::array<double, 3> centre{0, 0, 0};  ///< plane: the normal
  double radius = 0;                      ///< plane: d; sphere: the radius
  std::array<double, 3> size{0, 0, 0};    ///< box: half sizes along its own axes
  std::array<double, 3> angles{0, 0, 0};  ///< box: rotation about x, then y, then z, degrees
  bool operator==(const Probe&) const = default;
};

/// How the probes combine into the solid that stays: all of them, any of them, or the first
/// minus the others.
enum class ProbeOp : std::uint8_t { intersect, unite, subtract };

/// Parses a probe: "plane:A,B,C,D" (normal, offset: keeps A·x + B·y + C·z ≤ D; the normal is
/// normalised), "sphere:X,Y,Z,R" or "box:X,Y,Z,HX,HY,HZ[,AX,AY,AZ]" (centre, half sizes,
/// rotation in degrees). Throws UsageError quoting the text and what was expected.
Probe parse_probe(const std::string& text);
/// Parses "intersect", "union" or "subtract"; throws UsageError.
ProbeOp parse_probe_op(const std::string& text);
/// The text parse_probe reads back (round trip). Never throws.
std::string to_string(const Probe& p);
/// "intersect", "union" or "subtract".
const char* to_string(ProbeOp op);
/// Moves p by d (physical units): a sphere's or a box's centre; a plane along its normal by
/// d's share of it. Never throws.
void move_probe(Probe& p, const std::array<double, 3>& d);

/// The clip solid: probes in physical coordinates combined by op, over a grid whose voxel (i, j,
/// k) lies at origin + (i, j, k)·spacing. Empty (no probe): everything is kept.
class ClipRegion {
 public:
  /// Largest number of probes (the shader's uniform arrays).
  static constexpr int kMaxProbes = 8;
  ClipRegion() = default;
  /// Throws UsageError for more than kMaxProbes probes, a non-positive radius or half size, a
  /// zero plane normal or non-finite numbers.
  ClipRegion(std::vector<Probe> probes, ProbeOp op, std::array<double, 3> origin,
             std::array<double, 3> spacing);
  /// True when there are probes.
  bool active() const { return !probes_.empty(); }
  /// Signed distance (physical units; negative inside) of the solid at physical point p: max,
  /// min, or max(first, −others) of the probes' distances (exact for one probe, a bound for
  /// CSG). Never throws.
  double distance(const std::array<double, 3>& p) const;
  /// True when sample-coordinate point q stays (distance ≤ 0).
  bool kept(const std::array<double, 3>& q) const;
  /// Where the sample-coordinate box, grown by margin sample units on every side, lies (a
  /// ClipSide, tsp/tree/marks.h): wholly
  /// kept, wholly removed, or across the surface (conservative: a box reported across may lie
  /// on one side). Never throws.
  ClipSide classify(const Aabb& box, double margin = 0) const;
  /// Per octree node, its ClipSide with a margin (what the traversal and the LOD cut read): the
  /// renderer uses one voxel, so the surface passes through textured bricks only, never along a
  /// face between a kept and a removed one. Empty when not active.
  std::vector<ClipSide> classify_nodes(const Octree& octree, double margin = 0) const;
  /// A box (sample coordinates) holding every kept point of the sample-coordinate box domain —
  /// exact for planes, spheres and boxes alone, conservative for their combinations — or an
  /// empty one (lo > hi) when nothing of domain is kept; domain itself when not active. Never
  /// throws.
  Aabb bound(const Aabb& domain) const;
  /// The probes, the op, and the grid's geometry.
  const std::vector<Probe>& probes() const { return probes_; }
  ProbeOp op() const { return op_; }
  const std::array<double, 3>& origin() const { return origin_; }
  const std::array<double, 3>& spacing() const { return spacing_; }
  /// Box probes' rotations (physical → probe frame), row-major 3×3 per probe (identity for the
  /// others), for the shader.
  const std::vector<std::array<double, 9>>& rotations() const { return rotations_; }
  bool operator==(const ClipRegion& o) const {
    return probes_ == o.probes_ && op_ == o.op_ && origin_ == o.origin_ && spacing_ == o.spacing_;
  }

 private:
  std::vector<Probe> probes_;
  ProbeOp op_ = ProbeOp::intersect;
  std::array<double, 3> origin_{0, 0, 0}, spacing_{1, 1, 1};
  std::vector<std::array<double, 9>> rotations_;
  double probe_distance(int i, const std::array<double, 3>& p) const;
  ClipSide probe_side(int i, const std::array<double, 3>& lo, const std::array<double, 3>& hi) const;
  Aabb probe_bound(int i, const std::array<double, 3>& lo, const std::array<double, 3>& hi) const;
};

}  // namespace tsp
