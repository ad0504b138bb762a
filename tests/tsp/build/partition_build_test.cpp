// A build split over processes (tsp::BuildPartition) without MPI: ranks as threads of one
// process, exchanging bricks through an in-memory queue. The file rank 0 writes equals the
// serial build's bit for bit, with and without a stencil, whatever the rank count; tspplay-mpi
// runs the same code over MPI (tests/mpi).
#include <gtest/gtest.h>

#include <algorithm>
#include <condition_variable>
#include <deque>
#include <exception>
#include <filesystem>
#include <functional>
#include <limits>
#include <mutex>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "support/memory_source.h"
#include "support/paths.h"
#include "support/tsp_compare.h"
#include "tsp/build/build.h"
#include "tsp/store/tsp_file.h"

namespace {

namespace fs = std::filesystem;

// What the ranks share: the queue of bricks for rank 0 and the histogram sum.
struct Hub {
  explicit Hub(int n) : ranks(n) {}
  const int ranks;
  std::mutex mutex;
  std::condition_variable changed;
  std::deque<std::pair<int, tsp::BrickResult>> bricks;  // with the sender's pass
  std::vector<std::vector<std::uint64_t>> sum;           // per pass
  std::vector<int> summed;  // per pass: ranks other than 0 that added to sum
  // Pass 1: samples in flight to each rank (with the sender's pass), and the combined scans.
  std::vector<std::deque<std::pair<int, tsp::StepSamples>>> samples =
      std::vector<std::deque<std::pair<int, tsp::StepSamples>>>(std::size_t(ranks));
  struct Scan {
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    std::int64_t nonfinite = 0;
    int ranks = 0;  // contributed so far
  };
  std::vector<Scan> scans;  // per pass
};

class ThreadPartition final : public tsp::BuildPartition {
 public:
  ThreadPartition(Hub& hub, int rank) : hub_(hub), rank_(rank) {}
  int rank() const override { return rank_; }
  int ranks() const override { return hub_.ranks; }
  void send(const tsp::BrickResult& r) override {
    std::lock_guard lock(hub_.mutex);
    hub_.bricks.emplace_back(pass_, r);
    hub_.changed.notify_all();
  }
  tsp::BrickResult receive() override {
    std::unique_lock lock(hub_.mutex);
    auto mine = hub_.bricks.end();
    hub_.changed.wait(lock, [&] {
      mine = std::find_if(hub_.bricks.begin(), hub_.bricks.end(),
                          [&](const auto& m) { return m.first == pass_; });
      return mine != hub_.bricks.end();
    });
    tsp::BrickResult r = std::move(mine->second);
    hub_.bricks.erase(mine);
    return r;
  }
  void send_samples(const tsp::StepSamples& s, std::span<const float> samples) override {
    tsp::StepSamples m = s;
    m.samples.assign(samples.begin(), samples.end());
    std::lock_guard lock(hub_.mutex);
    hub_.samples[std::size_t(owner(s.brick))].emplace_back(pass_, std::move(m));
    hub_.changed.notify_all();
  }
  tsp::StepSamples receive_samples() override {
    std::unique_lock lock(hub_.mutex);
    auto& inbox = hub_.samples[std::size_t(rank_)];
    auto mine = inbox.end();
    hub_.changed.wait(lock, [&] {
      mine = std::find_if(inbox.begin(), inbox.end(),
                          [&](const auto& m) { return m.first == pass_; });
      return mine != inbox.end();
    });
    tsp::StepSamples s = std::move(mine->second);
    inbox.erase(mine);
    return s;
  }
  void combine_scan(float& lo, float& hi, std::int64_t& nonfinite) override {
    std::unique_lock lock(hub_.mutex);
    const std::size_t p = std::size_t(pass_);
    if (hub_.scans.size() <= p) hub_.scans.resize(p + 1);
    Hub::Scan& s = hub_.scans[p];
    s.lo = std::min(s.lo, lo);
    s.hi = std::max(s.hi, hi);
    s.nonfinite += nonfinite;
    ++s.ranks;
    hub_.changed.notify_all();
    hub_.changed.wait(lock, [&] { return hub_.scans[p].ranks == hub_.ranks; });
    lo = hub_.scans[p].lo;
    hi = hub_.scans[p].hi;
    nonfinite = hub_.scans[p].nonfinite;
  }
  void sum_to_writer(std::span<std::uint64_t> v) override {
    std::unique_lock lock(hub_.mutex);
    const std::size_t p = std::size_t(pass_++);
    if (hub_.sum.size() <= p) hub_.sum.resize(p + 1), hub_.summed.resize(p + 1, 0);
    if (rank_ != 0) {
      hub_.sum[p].resize(v.size(), 0);
      for (std::size_t i = 0; i < v.size(); ++i) hub_.sum[p][i] += v[i];
      ++hub_.summed[p];
      hub_.changed.notify_all();
      return;
    }
    hub_.changed.wait(lock, [&] { return hub_.summed[p] == hub_.ranks - 1; });
    for (std::size_t i = 0; i < hub_.sum[p].size(); ++i) v[i] += hub_.sum[p][i];
  }

 private:
  Hub& hub_;
  int rank_;
  int pass_ = 0;
};

// A wavy series with a stencil: x + y < 30 inside (an oblique face through the bricks).
class WedgeSource final : public tsp::VolumeSource {
 public:
  tsp::Dims dims() const override { return {37, 29, 21}; }
  int steps() const override { return 5; }
  std::string describe() const override { return "wedge"; }
  bool has_stencil() const override { return true; }
  void read_step(int t, std::span<float> out) override {
    std::vector<std::uint8_t> inside(out.size());
    read_step_inside(t, out, inside);
  }
  void read_step_inside(int t, std::span<float> out, std::span<std::uint8_t> inside) override {
    const tsp::Dims d = dims();
    for (int z = 0, i = 0; z < d.z; ++z)
      for (int y = 0; y < d.y; ++y)
        for (int x = 0; x < d.x; ++x, ++i) {
          inside[std::size_t(i)] = x + y < 30 + t ? 1 : 0;
          out[std::size_t(i)] = inside[std::size_t(i)] ? float(x * y % 7 + z + t * 0.25) : -1e6f;
        }
  }
};

tsptest::MemorySource wavy() {
  return tsptest::MemorySource::from_function({37, 29, 21}, 5, [](int x, int y, int z, int t) {
    return float((x * 3 + y * 5 + z * 7 + t * 11) % 17) + (x > 20 ? 100.f : 0.f);
  });
}

// Runs build(rank, partition) on `ranks` threads, one partition each over one hub; rethrows
// the first rank's exception. Returns how many bricks were sent but never received.
std::size_t run_ranks(int ranks,
                      const std::function<void(int, tsp::BuildPartition&)>& build) {
  Hub hub(ranks);
  std::vector<ThreadPartition> parts;
  for (int r = 0; r < ranks; ++r) parts.emplace_back(hub, r);
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(ranks));
  std::vector<std::thread> threads;
  for (int r = 0; r < ranks; ++r)
    threads.emplace_back([&, r] {
      try {
        build(r, parts[std::size_t(r)]);
      } catch (...) {
        errors[std::size_t(r)] = std::current_exception();
      }
    });
  for (auto& t : threads) t.join();
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
  return hub.bricks.size();
}

// Builds `make()`'s series serially to dir/serial.tsp and with `ranks` thread-ranks to
// dir/split.tsp (with split_slabs, the ranks read slabs where the serial build reads whole
// steps), and compares them.
template <class MakeSource>
void expect_split_equals_serial(const MakeSource& make, int ranks, bool split_slabs = false) {
  const fs::path dir = tsptest::temp_dir();
  tsp::BuildOptions options;
  options.brick_size = 8;
  options.threads = 2;
  auto serial_source = make();
  tsp::build_tsp_file(serial_source, (dir / "serial.tsp").string(), options);

  const std::size_t left = run_ranks(ranks, [&](int, tsp::BuildPartition& part) {
    auto source = make();
    if constexpr (requires { source.set_reads_slabs(true); }) source.set_reads_slabs(split_slabs);
    tsp::BuildOptions o = options;
    o.partition = &part;
    tsp::build_tsp_file(source, (dir / "split.tsp").string(), o);
  });
  EXPECT_EQ(left, 0u);
  tsptest::expect_same_build(dir / "serial.tsp", dir / "split.tsp", ranks);
  // Only rank 0 wrote: no other file (no temporaries) in the directory.
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir)) files += e.is_regular_file();
  EXPECT_EQ(files, 2);
}

TEST(PartitionBuild, RanksWriteTheSerialFile) {
  for (int ranks : {1, 2, 3, 5}) {
    SCOPED_TRACE(ranks);
    expect_split_equals_serial(wavy, ranks);
  }
}

TEST(PartitionBuild, RanksReadingSlabsWriteTheSerialFileOfWholeSteps) {
  for (int ranks : {1, 3}) {
    SCOPED_TRACE(ranks);
    expect_split_equals_serial(wavy, ranks, true);
  }
}

TEST(PartitionBuild, WithAStencil) {
  for (int ranks : {2, 4}) {
    SCOPED_TRACE(ranks);
    expect_split_equals_serial([] { return WedgeSource(); }, ranks);
  }
}

// Two fields, one pass each: a rank that finished the first may send bricks of the second
// while rank 0 still receives the first's.
TEST(PartitionBuild, SeveralFields) {
  const fs::path dir = tsptest::temp_dir();
  const std::vector<std::string> fields = {"a", "b", "c"};
  auto open_field = [](const std::string& f) {
    const float k = float(f[0] - 'a');
    return std::make_unique<tsptest::MemorySource>(tsptest::MemorySource::from_function(
        {37, 29, 21}, 5, [k](int x, int y, int z, int t) {
          return float((x * 3 + y * 5 + z * 7 + t * 11) % 17) * (k + 1) + k * 100;
        }));
  };
  tsp::BuildOptions options;
  options.brick_size = 8;
  tsp::build_tsp_fields(open_field, fields, (dir / "serial.tsp").string(), options);
  for (int ranks : {2, 3}) {
    SCOPED_TRACE(ranks);
    const fs::path out = dir / ("split" + std::to_string(ranks) + ".tsp");
    // Rank 1 runs ahead (3 ranks): rank 2 computes its bricks of the first field only once
    // rank 1 has sent its own and opened the second field, so rank 0 receives the second
    // field's messages while it still waits for the first's bricks from rank 2. (The fields'
    // input scans are combined across ranks: no rank can be a whole field ahead.)
    std::mutex m;
    std::condition_variable opened;
    bool rank1_on_second = false, held = false;
    run_ranks(ranks, [&](int r, tsp::BuildPartition& part) {
      tsp::BuildOptions o = options;
      o.partition = &part;
      if (ranks == 3 && r == 2)
        o.progress = [&](const std::string& phase, std::int64_t, std::int64_t) {
          if (phase.rfind(fields[0] + " ", 0) != 0 || phase.find("bricks") == std::string::npos)
            return;
          std::unique_lock<std::mutex> lock(m);
          held = true;
          opened.wait(lock, [&] { return rank1_on_second; });
        };
      auto open_in_order = [&](const std::string& f) {
        if (r == 1 && f == fields[1]) {
          {
            const std::lock_guard<std::mutex> lock(m);
            rank1_on_second = true;
          }
          opened.notify_all();
        }
        return open_field(f);
      };
      tsp::build_tsp_fields(open_in_order, fields, out.string(), o);
    });
    EXPECT_EQ(held, ranks == 3);  // rank 2 did wait for rank 1 to run ahead
    for (const std::string& f : fields)
      tsptest::expect_same_build(dir / "serial.tsp", out, ranks, f);
  }
}

TEST(PartitionBuild, SerialFileSaysOneRank) {
  const fs::path dir = tsptest::temp_dir();
  auto source = wavy();
  tsp::BuildOptions options;
  options.brick_size = 8;
  tsp::build_tsp_file(source, (dir / "a.tsp").string(), options);
  EXPECT_EQ(tsp::TspFile::open((dir / "a.tsp").string())->metadata().build_ranks, 1);
}

}  // namespace
