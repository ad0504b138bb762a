// Shared machinery of the built-in datasets (internal to tsp/source/procedural/*.cpp and the tests):
// size bookkeeping, normalised coordinates and the z-slab thread split of read_step.
#pragma once
#include <cstdint>
#include <memory>
#include <string>

#include "tsp/source/procedural/generated_source.h"

namespace tsp {

/// Normalised grid coordinate of sample i on an axis of n samples: i/(n−1), or 0.5 when n = 1.
inline double normalised(int i, int n) {
  return n > 1 ? double(i) / double(n - 1) : 0.5;
}
/// Normalised time of step t of T: t/(T−1), or 0 when T = 1.
inline double normalised_time(int t, int steps) {
  return steps > 1 ? double(t) / double(steps - 1) : 0.0;
}

/// A GeneratedSource whose steps are filled slab by slab, the slabs spread over threads.
class ProceduralSource : public GeneratedSource {
 public:
  /// Sizes are validated by make_generated_source; threads ≤ 0 means hardware concurrency.
  ProceduralSource(std::string name, Dims dims, int steps, std::uint64_t seed, int threads);
  Dims dims() const override { return dims_; }
  int steps() const override { return steps_; }
  std::string describe() const override;
  const std::string& name() const override { return name_; }
  std::uint64_t seed() const override { return seed_; }
  /// Fills step t; values never depend on the thread count (each voxel is computed by one thread
  /// in a fixed order). t and out.size() must be valid (asserted).
  void read_step(int t, std::span<float> out) final;
  bool reads_slabs() const final { return true; }
  /// Fills planes z0 … z1 − 1 of step t, the same values read_step gives them (asserted sizes).
  void read_slab(int t, int z0, int z1, std::span<float> out) final;

 protected:
  /// Writes every voxel of z-slices [z0, z1) of the step at normalised time tau into slab (which
  /// points at plane z0, x fastest). Called concurrently for disjoint slabs.
  virtual void fill_slab(double tau, int z0, int z1, float* slab) const = 0;

 private:
  std::string name_;
  Dims dims_;
  int steps_;
  std::uint64_t seed_;
  int threads_;
};

/// The "shock" dataset (generate_shock.cpp).
std::unique_ptr<GeneratedSource> make_shock(Dims dims, int steps, std::uint64_t seed, int threads);
/// The "vortex" dataset (generate_vortex.cpp).
std::unique_ptr<GeneratedSource> make_vortex(Dims dims, int steps, std::uint64_t seed, int threads);

}  // namespace tsp
