#include "mpi/mpi_partition.h"

#include <algorithm>
#include <climits>
#include <string>

#include "tsp/core/error.h"

namespace tspmpi {
namespace {

// Message kinds: a brick's header, then its payloads (MPI keeps messages of one sender and tag
// in order, so pieces of successive bricks cannot cross). Each pass has its own kTagsPerPass
// tags, so a rank already in the next pass cannot feed rank 0's current one.
enum Kind : int { kHeader = 0, kCodes, kInside, kStats, kTagsPerPass };
// Passes (fields of one build) before the tags wrap around; MPI guarantees tags up to 32767.
constexpr int kPassesBeforeWrap = 32767 / kTagsPerPass;
// Fields of the header: brick, codes, inside and stats sizes (elements), inside voxels.
constexpr int kHeaderFields = 5;
// Bytes per MPI message: counts are ints.
constexpr std::size_t kPieceBytes = std::size_t(1) << 30;

void check(int rc, const char* what) {
  if (rc == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int len = 0;
  MPI_Error_string(rc, text, &len);
  throw tsp::Error(std::string("MPI: ") + what + " failed: " + std::string(text, std::size_t(len)));
}

void send_bytes(const void* data, std::size_t bytes, int tag, MPI_Comm comm) {
  const char* p = static_cast<const char*>(data);
  for (std::size_t done = 0; done < bytes; done += kPieceBytes) {
    const int n = int(std::min(kPieceBytes, bytes - done));
    check(MPI_Send(p + done, n, MPI_BYTE, 0, tag, comm), "sending a brick");
  }
}

void receive_bytes(void* data, std::size_t bytes, int source, int tag, MPI_Comm comm) {
  char* p = static_cast<char*>(data);
  for (std::size_t done = 0; done < bytes; done += kPieceBytes) {
    const int n = int(std::min(kPieceBytes, bytes - done));
    check(MPI_Recv(p + done, n, MPI_BYTE, source, tag, comm, MPI_STATUS_IGNORE),
          "receiving a brick");
  }
}

}  // namespace

MpiPartition::MpiPartition(MPI_Comm comm) : comm_(comm) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &ranks_);
  MPI_Comm node;
  if (MPI_Comm_split_type(comm_, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node) ==
      MPI_SUCCESS) {
    MPI_Comm_size(node, &on_node_);
    MPI_Comm_free(&node);
  }
}

int MpiPartition::tag(int kind) const { return (pass_ % kPassesBeforeWrap) * kTagsPerPass + kind; }

void MpiPartition::send(const tsp::BrickResult& r) {
  const std::int64_t header[kHeaderFields] = {r.brick, std::int64_t(r.codes.size()),
                                              std::int64_t(r.inside.size()),
                                              std::int64_t(r.stats.size()), r.inside_voxels};
  check(MPI_Send(header, kHeaderFields, MPI_INT64_T, 0, tag(kHeader), comm_), "sending a brick");
  send_bytes(r.codes.data(), r.codes.size() * sizeof(std::uint16_t), tag(kCodes), comm_);
  send_bytes(r.inside.data(), r.inside.size(), tag(kInside), comm_);
  send_bytes(r.stats.data(), r.stats.size(), tag(kStats), comm_);
}

tsp::BrickResult MpiPartition::receive() {
  std::int64_t header[kHeaderFields];
  MPI_Status status;
  check(MPI_Recv(header, kHeaderFields, MPI_INT64_T, MPI_ANY_SOURCE, tag(kHeader), comm_,
                 &status),
        "receiving a brick");
  const int from = status.MPI_SOURCE;
  if (header[1] < 0 || header[2] < 0 || header[3] < 0 || header[0] < 0 || header[0] > INT_MAX)
    throw tsp::Error("MPI: rank " + std::to_string(from) + " sent a brick header with negative "
                     "sizes");
  tsp::BrickResult r;
  r.brick = int(header[0]);
  r.inside_voxels = header[4];
  r.codes.resize(std::size_t(header[1]));
  r.inside.resize(std::size_t(header[2]));
  r.stats.resize(std::size_t(header[3]));
  receive_bytes(r.codes.data(), r.codes.size() * sizeof(std::uint16_t), from, tag(kCodes), comm_);
  receive_bytes(r.inside.data(), r.inside.size(), from, tag(kInside), comm_);
  receive_bytes(r.stats.data(), r.stats.size(), from, tag(kStats), comm_);
  return r;
}

void MpiPartition::sum_to_writer(std::span<std::uint64_t> v) {
  check(MPI_Reduce(rank_ == 0 ? MPI_IN_PLACE : v.data(), v.data(), int(v.size()), MPI_UINT64_T,
                   MPI_SUM, 0, comm_),
        "summing the histogram");
  ++pass_;
}

}  // namespace tspmpi
