// The LOD level bricks' filter (spec §14, docs/formats.md "Levels"): a level brick's sample at
// voxel coordinate p with spacing f along an axis is a separable box filter of width f centred on
// p — weights ½, 1, …, 1, ½ over p − f/2 … p + f/2, the box of one coarse cell integrated with
// linear interpolation — whose window shrinks symmetrically at the grid's faces. The value depends
// on p and f only, never on the node, so neighbours at one level agree on shared faces (Leven's
// border continuity), and a linear field is reproduced exactly at every level.
//
// LevelStream computes it from one step's planes fed in z order, holding only the planes a
// window still needs, so a build never needs a whole step in memory; filter_level is the same
// stream fed a whole volume, so both give the same bits.
#pragma once
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "tsp/core/types.h"
#include "tsp/tree/octree.h"

namespace tsp {

namespace detail {
/// The filter taps of one output sample along an axis: voxels first … first + weights.size() − 1.
struct FilterTaps {
  int first = 0;
  std::vector<float> weights;
};
}  // namespace detail

/// One level brick's filtered samples (and, given its own box, its residual) computed from one
/// step's planes in z order. Not thread-safe; one stream per level brick.
class LevelStream {
 public:
  /// Plane z of the step (d.x · d.y floats, x fastest), for z in [needs_from(), end of feed).
  using PlaneFn = std::function<const float*(int z)>;
  /// A stream for lattice l of a grid d; with own (the node's box) it also sums the residual
  /// (level_residual) over own; with clamp, finite samples are clamped first. Never throws.
  LevelStream(Dims d, const BrickLattice& l, std::optional<Box> own,
              std::optional<ValueRange> clamp);
  /// Starts the next step, keeping the buffers. Never throws.
  void restart();
  /// Lowest plane it will still read; d.z once done. Planes below it may be dropped. Never
  /// throws.
  int needs_from() const;
  /// Reads the planes from needs_from() up to end − 1 that its windows can use now. Never throws.
  void feed(const PlaneFn& plane, int end);
  /// True when every sample (and the residual) is computed. Never throws.
  bool done() const { return needs_from() >= dims_.z; }
  /// The filtered samples, l.count() floats, x fastest; complete once done(), until release().
  /// Never throws.
  const std::vector<float>& samples() const { return out_; }
  /// Frees the samples (made again by the next step's feed). Never throws.
  void release();
  /// The residual over own (0 without own or without a finite voxel); final once done().
  double residual() const;

 private:
  void reduce_plane(const float* plane);
  Dims dims_;
  BrickLattice lattice_;
  std::optional<Box> own_;
  std::optional<ValueRange> clamp_;
  std::vector<detail::FilterTaps> taps_[3];  // each axis's samples
  int lo_[3] = {}, len_[3] = {};
  // Per own voxel along each axis: its lower lattice sample and its weight towards the next.
  std::vector<int> res_k_[3];
  std::vector<float> res_t_[3];
  int next_reduce_ = 0;   // next plane to reduce in x and y
  int reduced_lo_ = 0;    // plane of reduced_'s first reduced plane
  int next_sample_ = 0;   // next z sample of the lattice to compute
  int next_residual_ = 0; // next plane of own whose residual is summed
  double sum_ = 0;
  std::int64_t count_ = 0;
  std::vector<float> reduced_;  // reduced planes [reduced_lo_, next_reduce_), my·mx each
  std::vector<float> a_, b_;    // one plane's window and its x pass
  std::vector<float> out_;
};

/// Fills out with the level brick of lattice l (l.count() floats, x fastest) filtered from one
/// step's volume vol (d.count() floats, x fastest). With clamp, finite samples are clamped into it
/// first; non-finite samples are left out of the averages (NaN when a window has none, which the
/// builder's sanitizer then maps like any NaN). Never throws (asserts sizes).
void filter_level(std::span<const float> vol, Dims d, const BrickLattice& l,
                  const std::optional<ValueRange>& clamp, std::vector<float>& out);

/// RMS difference over the finite voxels of own between vol and the trilinear reconstruction of
/// them from level (the output of filter_level for l); 0 when own has no finite voxel.
double level_residual(std::span<const float> vol, Dims d, const BrickLattice& l, const Box& own,
                      std::span<const float> level, const std::optional<ValueRange>& clamp);

}  // namespace tsp
