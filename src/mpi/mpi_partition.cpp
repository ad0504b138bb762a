#include "mpi/mpi_partition.h"

#include <algorithm>
#include <chrono>
#include <climits>
#include <thread>
#include <cstring>
#include <vector>
#include <string>

#include <hdf5.h>

#include "tsp/core/error.h"

namespace tspmpi {
namespace {

// Message kinds: a brick's header, then its payloads (MPI keeps messages of one sender and tag
// in order, so pieces of successive bricks cannot cross). Each pass has its own kTagsPerPass
// tags, so a rank already in the next pass cannot feed rank 0's current one.
enum Kind : int { kHeader = 0, kCodes, kInside, kStats, kSamples, kTagsPerPass };
// A samples message: brick, step, stencil flag (int32 each) and the residual (float32), then
// the samples.
constexpr std::size_t kSamplesHeader = 4 * sizeof(std::int32_t);
// Passes (fields of one build) before the tags wrap around; MPI guarantees tags up to 32767.
constexpr int kPassesBeforeWrap = 32767 / kTagsPerPass;
// Fields of the header: brick, codes, inside and stats sizes (elements), inside voxels.
constexpr int kHeaderFields = 5;
// Bytes per MPI message: counts are ints.
constexpr std::size_t kPieceBytes = std::size_t(1) << 30;

// Polling instead of a blocking receive: Open MPI's blocking calls spin on a core, which the
// rank's own workers need while its receiver waits.
constexpr auto kPollInterval = std::chrono::microseconds(50);

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

void MpiPartition::wait_for(int tag, MPI_Message* message, MPI_Status* status) const {
  for (;;) {
    int found = 0;
    check(MPI_Improbe(MPI_ANY_SOURCE, tag, comm_, &found, message, status),
          "waiting for a message");
    if (found) return;
    std::this_thread::sleep_for(kPollInterval);
  }
}

void MpiCollectiveIo::set_file_access(std::int64_t fapl) {
  if (H5Pset_fapl_mpio(hid_t(fapl), comm_, MPI_INFO_NULL) < 0)
    throw tsp::Error("parallel HDF5: cannot set MPI-IO file access");
}

void MpiCollectiveIo::set_collective_transfer(std::int64_t dxpl) {
  if (H5Pset_dxpl_mpio(hid_t(dxpl), H5FD_MPIO_COLLECTIVE) < 0)
    throw tsp::Error("parallel HDF5: cannot set collective transfers");
}

void MpiCollectiveIo::barrier() { check(MPI_Barrier(comm_), "waiting for every rank"); }

std::string MpiPartition::broadcast_path(const std::string& path) {
  std::uint64_t n = path.size();
  check(MPI_Bcast(&n, 1, MPI_UINT64_T, 0, comm_), "sharing the output's name");
  std::string out = rank_ == 0 ? path : std::string(n, '\0');
  check(MPI_Bcast(out.data(), int(n), MPI_CHAR, 0, comm_), "sharing the output's name");
  return out;
}

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
  std::lock_guard lock(send_mutex_);
  check(MPI_Send(header, kHeaderFields, MPI_INT64_T, 0, tag(kHeader), comm_), "sending a brick");
  send_bytes(r.codes.data(), r.codes.size() * sizeof(std::uint16_t), tag(kCodes), comm_);
  send_bytes(r.inside.data(), r.inside.size(), tag(kInside), comm_);
  send_bytes(r.stats.data(), r.stats.size(), tag(kStats), comm_);
}

tsp::BrickResult MpiPartition::receive() {
  std::int64_t header[kHeaderFields];
  MPI_Message message;
  MPI_Status status;
  wait_for(tag(kHeader), &message, &status);
  check(MPI_Mrecv(header, kHeaderFields, MPI_INT64_T, &message, MPI_STATUS_IGNORE),
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

void MpiPartition::send_samples(const tsp::StepSamples& s, std::span<const float> samples) {
  std::vector<char> buf(kSamplesHeader + samples.size() * sizeof(float));
  const std::int32_t head[3] = {s.brick, s.step, s.stencil ? 1 : 0};
  std::memcpy(buf.data(), head, sizeof(head));
  std::memcpy(buf.data() + sizeof(head), &s.residual, sizeof(float));
  std::memcpy(buf.data() + kSamplesHeader, samples.data(), samples.size() * sizeof(float));
  if (buf.size() > std::size_t(INT_MAX)) throw tsp::Error("MPI: a brick of over 2 GiB");
  check(MPI_Send(buf.data(), int(buf.size()), MPI_BYTE, owner(s.brick), tag(kSamples), comm_),
        "sending samples");
}

tsp::StepSamples MpiPartition::receive_samples() {
  MPI_Message message;
  MPI_Status status;
  wait_for(tag(kSamples), &message, &status);
  int bytes = 0;
  MPI_Get_count(&status, MPI_BYTE, &bytes);
  std::vector<char> buf(std::size_t(std::max(bytes, 0)));
  check(MPI_Mrecv(buf.data(), bytes, MPI_BYTE, &message, MPI_STATUS_IGNORE), "receiving samples");
  if (buf.size() < kSamplesHeader || (buf.size() - kSamplesHeader) % sizeof(float) != 0)
    throw tsp::Error("MPI: rank " + std::to_string(status.MPI_SOURCE) +
                     " sent a samples message of " + std::to_string(bytes) + " bytes");
  std::int32_t head[3];
  std::memcpy(head, buf.data(), sizeof(head));
  tsp::StepSamples s;
  s.brick = head[0];
  s.step = head[1];
  s.stencil = head[2] != 0;
  std::memcpy(&s.residual, buf.data() + sizeof(head), sizeof(float));
  s.samples.resize((buf.size() - kSamplesHeader) / sizeof(float));
  std::memcpy(s.samples.data(), buf.data() + kSamplesHeader, s.samples.size() * sizeof(float));
  return s;
}

void MpiPartition::combine_scan(float& lo, float& hi, std::int64_t& nonfinite) {
  check(MPI_Allreduce(MPI_IN_PLACE, &lo, 1, MPI_FLOAT, MPI_MIN, comm_), "combining the scans");
  check(MPI_Allreduce(MPI_IN_PLACE, &hi, 1, MPI_FLOAT, MPI_MAX, comm_), "combining the scans");
  check(MPI_Allreduce(MPI_IN_PLACE, &nonfinite, 1, MPI_INT64_T, MPI_SUM, comm_),
        "combining the scans");
}

void MpiPartition::sum_to_writer(std::span<std::uint64_t> v) {
  check(MPI_Reduce(rank_ == 0 ? MPI_IN_PLACE : v.data(), v.data(), int(v.size()), MPI_UINT64_T,
                   MPI_SUM, 0, comm_),
        "summing the histogram");
  ++pass_;
}

}  // namespace tspmpi
