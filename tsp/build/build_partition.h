// tsp/build: a build split over processes (tspplay-mpi); may include core/. The library knows
// only this interface: the MPI executable implements it (src/mpi/), so tsp needs no MPI.
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace tsp {

class CollectiveIo;

/// One stored brick's results, shipped from the process that computed them to the writer.
struct BrickResult {
  int brick = -1;                     ///< stored brick: leaves first, then level bricks
  std::vector<std::uint16_t> codes;   ///< [T][Bz][By][Bx], as TspWriter::write_brick_series
  std::vector<std::uint8_t> inside;   ///< the stencil laid out like codes; empty without one
  std::vector<std::byte> stats;       ///< leaf: its NodeAccum per time node; level: residuals
  std::int64_t inside_voxels = 0;     ///< leaf with a stencil: own voxels inside at some step
};

/// One stored brick's samples at one step, sent in pass 1 by the process that read the step to
/// the one that owns the brick.
struct StepSamples {
  int brick = -1;              ///< stored brick: leaves first, then level bricks
  int step = -1;               ///< time step
  bool stencil = false;        ///< the brick's inside flags (as floats), not its values
  float residual = 0;          ///< level brick values: its residual at this step (level_errors)
  std::vector<float> samples;  ///< the brick's samples at the step, x fastest (received)
};

/// A build split over ranks() processes. Pass 1: process rank() reads the steps t with
/// t % ranks() == rank(), and sends each stored brick's samples at those steps to the brick's
/// owner (send_samples); the input scans are combined (combine_scan). Pass 2: process rank()
/// computes the stored bricks b with b % ranks() == rank(), and process 0 writes the file from
/// its own bricks and those the others send (send/receive). A build of several fields makes one
/// pass pair per field, each ending with sum_to_writer on every rank: a rank that has finished
/// may already send the next field's samples and bricks, and receive() and receive_samples()
/// must not return them before this process's own sum_to_writer of the current field
/// (implementations count fields and tag messages with it). A process calls send and
/// send_samples from several threads while one thread receives (MPI_THREAD_MULTIPLE).
class BuildPartition {
 public:
  virtual ~BuildPartition() = default;
  /// This process's index, 0 ≤ rank() < ranks(). Never throws.
  virtual int rank() const = 0;
  /// How many processes build the file, ≥ 1. Never throws.
  virtual int ranks() const = 0;
  /// Ranks other than 0: hands one brick's results to rank 0 (blocks until taken; may be called
  /// from several threads at once). Throws Error.
  virtual void send(const BrickResult& result) = 0;
  /// Rank 0: the next brick of the current pass, from whichever rank sent first. Throws Error.
  virtual BrickResult receive() = 0;
  /// Sums v element-wise over every rank into rank 0's v (collective), ending this process's
  /// current pass. Throws Error.
  virtual void sum_to_writer(std::span<std::uint64_t> v) = 0;
  /// Pass 1: sends a brick's samples at a step (s.samples empty: they are `samples`) to the
  /// brick's owner (blocks until taken; may be called from several threads at once). Throws
  /// Error.
  virtual void send_samples(const StepSamples& s, std::span<const float> samples) = 0;
  /// Pass 1: the next samples another process sent this one in the current pass. Throws Error.
  virtual StepSamples receive_samples() = 0;
  /// End of pass 1 (collective): the minimum of lo, the maximum of hi and the sum of nonfinite
  /// over every rank, into every rank's. Throws Error.
  virtual void combine_scan(float& lo, float& hi, std::int64_t& nonfinite) = 0;
  /// How the ranks write the file together (parallel HDF5: every rank writes its own bricks,
  /// rank 0 the tree), or null when rank 0 writes the whole file (the default). Never throws.
  virtual CollectiveIo* collective_io() { return nullptr; }
  /// Rank 0's path, returned on every rank (collective; with collective_io only). Throws Error.
  virtual std::string broadcast_path(const std::string& path) { return path; }
  /// The process that reads step t, or computes stored brick b (both round robin). Never throws.
  int owner(std::int64_t i) const { return int(i % ranks()); }
  /// Whether this process reads step t in pass 1. Never throws.
  bool reads(int t) const { return owner(t) == rank(); }
  /// Whether this process computes stored brick b. Never throws.
  bool owns(std::int64_t b) const { return owner(b) == rank(); }
  /// How many of the indices 0 … count − 1 (steps or stored bricks) are this process's. Never
  /// throws.
  std::int64_t share(std::int64_t count) const {
    return std::max<std::int64_t>(0, (count - rank() + ranks() - 1) / ranks());
  }
};

}  // namespace tsp
