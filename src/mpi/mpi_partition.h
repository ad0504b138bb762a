// tspplay-mpi: the build's partition over MPI ranks (tsp::BuildPartition over MPI_COMM_WORLD).
#pragma once
#include <mpi.h>

#include <mutex>
#include <string>

#include "tsp/build/build_partition.h"
#include "tsp/store/tsp_writer.h"

namespace tspmpi {

/// Parallel HDF5 over comm: MPI-IO file access, collective transfers, MPI_Barrier.
class MpiCollectiveIo final : public tsp::CollectiveIo {
 public:
  /// Uses comm (not duplicated: it must outlive this). Never throws.
  explicit MpiCollectiveIo(MPI_Comm comm) : comm_(comm) {}
  /// H5Pset_fapl_mpio over comm. Throws tsp::Error.
  void set_file_access(std::int64_t fapl) override;
  /// H5Pset_dxpl_mpio, collective. Throws tsp::Error.
  void set_collective_transfer(std::int64_t dxpl) override;
  /// MPI_Barrier over comm. Throws tsp::Error.
  void barrier() override;

 private:
  MPI_Comm comm_;
};

/// The ranks of comm build one file: point-to-point messages carry samples to the bricks'
/// owners (pass 1) and finished bricks to rank 0 (pass 2), reductions combine the input scans
/// and the histogram. Needs MPI initialised with MPI_THREAD_MULTIPLE (senders and a receiver
/// on different threads).
class MpiPartition final : public tsp::BuildPartition {
 public:
  /// Uses comm (not duplicated: it must outlive this). Never throws.
  explicit MpiPartition(MPI_Comm comm);
  /// This process's rank in comm. Never throws.
  int rank() const override { return rank_; }
  /// comm's size. Never throws.
  int ranks() const override { return ranks_; }
  /// Sends result to rank 0: a header, then codes, stencil and statistics in pieces of at most
  /// 1 GiB, one brick at a time per process (they must not interleave). Thread-safe. Throws
  /// tsp::Error on an MPI error.
  void send(const tsp::BrickResult& result) override;
  /// Receives the next brick from any rank (header first, then its pieces from that rank).
  /// Throws tsp::Error on an MPI error or a header with negative sizes.
  tsp::BrickResult receive() override;
  /// MPI_Reduce (sum) of v into rank 0's v; the next messages belong to the next pass. Throws
  /// tsp::Error on an MPI error.
  void sum_to_writer(std::span<std::uint64_t> v) override;
  /// One message to the brick's owner: a small header, then the samples. Throws tsp::Error on
  /// an MPI error.
  void send_samples(const tsp::StepSamples& s, std::span<const float> samples) override;
  /// The next samples message of the current pass from any rank (matched probe, so the size is
  /// known before receiving). Throws tsp::Error on an MPI error or a malformed message.
  tsp::StepSamples receive_samples() override;
  /// MPI_Allreduce: MIN of lo, MAX of hi, SUM of nonfinite. Throws tsp::Error on an MPI error.
  void combine_scan(float& lo, float& hi, std::int64_t& nonfinite) override;
  /// Every rank writes its own bricks into the file with parallel HDF5. Never throws.
  tsp::CollectiveIo* collective_io() override { return &io_; }
  /// MPI_Bcast of rank 0's path. Throws tsp::Error on an MPI error.
  std::string broadcast_path(const std::string& path) override;
  /// Ranks of comm on this node (MPI_COMM_TYPE_SHARED). Never throws.
  int ranks_on_node() const { return on_node_; }

 private:
  int tag(int kind) const;  // kind's tag in the current pass
  // Waits (polling) for a message with this tag from any rank. Throws tsp::Error.
  void wait_for(int tag, MPI_Message* message, MPI_Status* status) const;

  MPI_Comm comm_;
  int rank_ = 0, ranks_ = 1, on_node_ = 1;
  int pass_ = 0;  // passes ended by sum_to_writer: messages of pass k carry tags of pass k
  std::mutex send_mutex_;  // a brick's messages leave together
  MpiCollectiveIo io_{comm_};
};

}  // namespace tspmpi
