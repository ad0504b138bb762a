// tsp/build: a build split over processes (tspplay-mpi); may include core/. The library knows
// only this interface: the MPI executable implements it (src/mpi/), so tsp needs no MPI.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace tsp {

/// One stored brick's results, shipped from the process that computed them to the writer.
struct BrickResult {
  int brick = -1;                     ///< stored brick: leaves first, then level bricks
  std::vector<std::uint16_t> codes;   ///< [T][Bz][By][Bx], as TspWriter::write_brick_series
  std::vector<std::uint8_t> inside;   ///< the stencil laid out like codes; empty without one
  std::vector<std::byte> stats;       ///< leaf: its NodeAccum per time node; level: residuals
  std::int64_t inside_voxels = 0;     ///< leaf with a stencil: own voxels inside at some step
};

/// A build split over ranks() processes: process rank() computes the stored bricks b with
/// b % ranks() == rank() (every process reads every step), and process 0 writes the file from
/// its own bricks and those the others send. A build of several fields makes one pass per
/// field, each ending with sum_to_writer on every rank: a rank that has finished a pass may
/// already send the next pass's bricks, and receive() must not return them before rank 0's own
/// sum_to_writer of the current pass (implementations count passes and tag messages with it).
/// Each process calls its methods from one thread at a time (the builder serialises them), so
/// MPI_THREAD_SERIALIZED suffices.
class BuildPartition {
 public:
  virtual ~BuildPartition() = default;
  /// This process's index, 0 ≤ rank() < ranks(). Never throws.
  virtual int rank() const = 0;
  /// How many processes build the file, ≥ 1. Never throws.
  virtual int ranks() const = 0;
  /// Ranks other than 0: hands one brick's results to rank 0 (blocks until taken). Throws Error.
  virtual void send(const BrickResult& result) = 0;
  /// Rank 0: the next brick of the current pass, from whichever rank sent first. Throws Error.
  virtual BrickResult receive() = 0;
  /// Sums v element-wise over every rank into rank 0's v (collective), ending this process's
  /// current pass. Throws Error.
  virtual void sum_to_writer(std::span<std::uint64_t> v) = 0;
  /// Whether this process computes stored brick b. Never throws.
  bool owns(std::int64_t b) const { return b % ranks() == rank(); }
};

}  // namespace tsp
