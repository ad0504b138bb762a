#include "tsp/build/brick_pass.h"

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <map>
#include <optional>
#include <mutex>
#include <string>
#include <utility>

#include "tsp/build/brick_stats.h"
#include "tsp/core/background_worker.h"
#include "tsp/core/error.h"
#include "tsp/core/parallel_for.h"
#include "tsp/store/tsp_layout.h"

namespace tsp::detail {
namespace {

// NaN and −Inf become lo, +Inf hi; everything is clamped into [lo, hi].
void sanitize(std::span<float> v, ValueRange r) {
  const float lo = float(r.lo), hi = float(r.hi);
  for (float& x : v) x = std::isnan(x) ? lo : std::clamp(x, lo, hi);
}

// Bit-for-bit the same code as Quantizer::encode for sanitized (non-NaN) samples, without a libm
// call per sample: adding and subtracting 2^52 rounds half to even like nearbyint in the default
// rounding mode.
struct FastQuantizer {
  double lo, width;
  bool flat;
  explicit FastQuantizer(ValueRange r) : lo(r.lo), width(r.width()), flat(!(r.width() > 0)) {}
  std::uint16_t operator()(float v) const {
    if (flat) return 0;
    constexpr double kRound = 4503599627370496.0;  // 2^52
    double q = (double(v) - lo) / width * kQuantMax;
    q = (q + kRound) - kRound;
    // Branch-free clamp (v is never NaN here: sanitize() ran first); −0 converts to 0.
    q = std::min(std::max(q, 0.0), double(kQuantMax));
    return std::uint16_t(int(q));
  }
};

// Encodes a brick's series [T][samples] into the padded stored layout [T][Bz][By][Bx] (codes
// by q, stencil flags by a threshold), repeating the last sample along each axis into the
// padding.
template <typename T, typename Encode>
void quantize_padded(std::span<const float> series, const BrickLattice& s,
                     std::array<int, 3> shape, int steps, const Encode& q, std::vector<T>& out) {
  const int sx = s.samples[0], sy = s.samples[1], sz = s.samples[2];
  out.resize(std::size_t(steps) * shape[0] * shape[1] * shape[2]);
  T* o = out.data();
  for (int t = 0; t < steps; ++t) {
    const float* step = series.data() + std::size_t(t) * std::size_t(s.count());
    for (int z = 0; z < shape[2]; ++z)
      for (int y = 0; y < shape[1]; ++y) {
        const float* row =
            step + std::size_t(sx) * (std::min(y, sy - 1) + std::size_t(sy) * std::min(z, sz - 1));
        for (int x = 0; x < sx; ++x) o[x] = q(row[x]);
        for (int x = sx; x < shape[0]; ++x) o[x] = o[sx - 1];
        o += shape[0];
      }
  }
}

// A stencil flag from its (filtered) float: inside when at least half.
struct InsideFlag {
  std::uint8_t operator()(float v) const { return v >= 0.5f ? 1 : 0; }
};

// Histogram of the brick's own voxels over all steps: bin floor((v − lo)·bins/(hi − lo)),
// clamped to the last bin; everything in bin 0 for a zero-width range. With a stencil (mask:
// the series' flags) only inside voxels count.
void add_histogram(std::span<const float> series, std::span<const float> mask, const Box& s,
                   const Box& own, int steps, ValueRange r, std::vector<std::uint64_t>& hist) {
  const double scale = r.width() > 0 ? kHistogramBins / r.width() : 0;
  for (int t = 0; t < steps; ++t) {
    const float* step = series.data() + std::size_t(t) * s.count();
    for (int z = own.lo[2]; z < own.hi[2]; ++z)
      for (int y = own.lo[1]; y < own.hi[1]; ++y) {
        const float* row = step + std::size_t(s.size(0)) *
                                      ((y - s.lo[1]) + std::size_t(s.size(1)) * (z - s.lo[2]));
        for (int x = own.lo[0]; x < own.hi[0]; ++x) {
          if (!mask.empty() && mask[std::size_t(row - series.data()) + std::size_t(x - s.lo[0])] < 0.5f)
            continue;
          int bin = int((double(row[x - s.lo[0]]) - r.lo) * scale);
          hist[std::clamp(bin, 0, kHistogramBins - 1)]++;
        }
      }
  }
}

// Collective writes (parallel HDF5): in round k every rank writes its k-th brick (first +
// k·stride; nothing once it has none left), all ranks together in one collective write, on one
// thread per rank, while its workers compute the next bricks. One brick per round: a rank's
// bricks are not adjacent in the file, and HDF5 1.10 maps a strided selection of several
// chunks with filters element by element (measured on the 256³ shock, 2 ranks: 14 ms a round
// of one brick, 444 ms of two). Workers hand over finished bricks in any order and wait while
// they are more than `ahead` bricks past the one being written, so at most ahead + 1 bricks
// wait here. The writes are one job on a BackgroundWorker.
class OrderedWrites {
 public:
  /// Writes rounds 0 … rounds − 1 with writer on the worker's thread; this rank has `mine`
  /// bricks. Throws std::system_error when the thread cannot start.
  OrderedWrites(TspWriter& writer, std::int64_t rounds, std::int64_t mine, int first, int stride,
                std::int64_t ahead)
      : writer_(writer), rounds_(rounds), mine_(mine), first_(first), stride_(stride),
        ahead_(ahead), worker_([this] {
          std::lock_guard lock(mutex_);  // put() tests failed() under it: no lost wake-up
          cv_.notify_all();
        }) {
    worker_.submit([this](std::stop_token stop) { run(stop); });
  }
  /// Stops waiting (after a failure elsewhere) and joins the thread (the worker's destructor).
  ~OrderedWrites() = default;
  /// Hands over this rank's k-th brick; blocks while k is too far ahead of the writes. Rethrows
  /// the writes' exception when they failed. Thread-safe (the pass's workers call it).
  void put(std::int64_t k, std::vector<std::uint16_t> codes, std::vector<std::uint8_t> inside) {
    std::unique_lock lock(mutex_);
    cv_.wait(lock, worker_.stop_token(),
             [&] { return k <= next_ + ahead_ || worker_.failed(); });
    worker_.rethrow_if_failed();
    ready_[k] = {std::move(codes), std::move(inside)};
    cv_.notify_all();
  }
  /// Waits for every round to be written; rethrows the writes' exception. The owner's thread.
  void finish() { worker_.wait(); }

 private:
  void run(const std::stop_token& stop) {
    for (std::int64_t k = 0; k < rounds_; ++k) {
      if (k >= mine_) {
        writer_.write_no_brick();
      } else {
        std::pair<std::vector<std::uint16_t>, std::vector<std::uint8_t>> b;
        {
          std::unique_lock lock(mutex_);
          if (!cv_.wait(lock, stop, [&] { return ready_.count(k) != 0; })) return;  // stopped
          b = std::move(ready_[k]);
          ready_.erase(k);
        }
        const int brick = int(first_ + k * stride_);
        writer_.write_brick_series(brick, b.first);
        if (!b.second.empty()) writer_.write_inside_series(brick, b.second);
      }
      std::lock_guard lock(mutex_);
      next_ = k + 1;
      cv_.notify_all();
    }
  }
  TspWriter& writer_;
  std::int64_t rounds_, mine_;
  int first_, stride_;
  std::int64_t ahead_;
  std::mutex mutex_;
  std::condition_variable_any cv_;  // a brick handed over or written, a failure, or stop
  std::map<std::int64_t, std::pair<std::vector<std::uint16_t>, std::vector<std::uint8_t>>> ready_;
  std::int64_t next_ = 0;  // the brick being written
  BackgroundWorker worker_;  // last: its thread ends before the members above go
};

// Pass 2: brick-major over the scratch file, on `threads` workers.
// With a partition, each process takes its own stored bricks; rank 0 writes them and those the
// other ranks send (absorb), the others send theirs instead of writing — or, with collective
// writes, every rank writes its own (OrderedWrites) and sends rank 0 only their statistics.
struct BrickPass {
  BrickPass(const TspTree& t, ScratchFile& s, ScratchFile& l, StencilScratch st, TspWriter* w,
            ValueRange r, std::vector<NodeAccum>& a, std::span<float> le, BuildPartition* p)
      : tree(t), scratch(s), levels(l), stencil(st), writer(w), range(r), acc(a),
        level_errors(le), part(p), inside_voxels(std::size_t(t.octree().stored_brick_count()), 0) {}
  const TspTree& tree;
  ScratchFile& scratch;
  ScratchFile& levels;
  StencilScratch stencil;
  TspWriter* writer;  // null on ranks other than 0 unless the writes are collective
  OrderedWrites* ordered = nullptr;  // collective writes: this rank's bricks in round order
  ValueRange range;
  std::vector<NodeAccum>& acc;  // by TSP node id; each worker fills its leaves' slices
  std::span<float> level_errors;  // [level brick][step]
  BuildPartition* part;           // null: one process builds everything
  std::vector<std::uint8_t> received = std::vector<std::uint8_t>(
      std::size_t(tree.octree().stored_brick_count()), 0);  // rank 0: bricks absorbed
  std::vector<std::uint64_t> histogram = std::vector<std::uint64_t>(kHistogramBins, 0);
  std::vector<std::int64_t> inside_voxels;  // per stored brick: own voxels inside at some step
                                            // (leaves, and the level bricks of stopped nodes)

  std::mutex mutex;  // guards progress calls
  int done = 0;

  // Per-worker buffers and histogram (merged after the pass, in worker order).
  struct Scratch {
    std::vector<float> series;
    std::vector<std::uint16_t> codes;
    std::vector<float> mask;          // the stencil's series, as floats
    std::vector<std::uint8_t> flags;  // padded stencil codes, or the union over steps
    std::vector<std::uint64_t> hist = std::vector<std::uint64_t>(kHistogramBins, 0);
  };

  void brick(int b, Scratch& w, const ProgressFn& progress, std::int64_t total_bytes) {
    const Octree& o = tree.octree();
    const TimeTree& time = tree.time();
    const int steps = time.steps();
    const Box s = o.brick_samples(b), own = o.brick_box(b);
    w.series.resize(std::size_t(s.count()) * steps);
    scratch.read_series(b, w.series);
    scratch.discard(b);
    sanitize(w.series, range);
    quantize_padded(w.series, o.lattice(b), stored_brick_shape(o), steps, FastQuantizer(range),
                    w.codes);
    BrickResult res;  // what a rank other than 0 ships instead of writing
    res.brick = b;
    put_codes(b, w.codes, res);
    std::span<const std::uint8_t> use;
    if (stencil.leaves) {
      w.mask.resize(w.series.size());
      stencil.leaves->read_series(b, w.mask);
      stencil.leaves->discard(b);
      quantize_padded(w.mask, o.lattice(b), stored_brick_shape(o), steps, InsideFlag{}, w.flags);
      put_inside(b, w.flags, res);
      // A voxel counts in the statistics when it is inside at some step (moving meshes).
      const std::size_t per = std::size_t(s.count());
      w.flags.assign(per, 0);
      for (int t = 0; t < steps; ++t)
        for (std::size_t i = 0; i < per; ++i)
          w.flags[i] |= w.mask[std::size_t(t) * per + i] >= 0.5f ? 1 : 0;
      use = w.flags;
      std::int64_t in = 0;
      for (int z = own.lo[2]; z < own.hi[2]; ++z)
        for (int y = own.lo[1]; y < own.hi[1]; ++y)
          for (int x = own.lo[0]; x < own.hi[0]; ++x)
            in += w.flags[std::size_t((x - s.lo[0]) +
                                      s.size(0) * ((y - s.lo[1]) + s.size(1) * (z - s.lo[2])))];
      inside_voxels[std::size_t(b)] = in;
      res.inside_voxels = in;
    }
    add_histogram(w.series, stencil.leaves ? std::span<const float>(w.mask) : std::span<const float>(),
                  s, own, steps, range, w.hist);
    std::span<NodeAccum> leaf(acc.data() + tree.id(o.brick_node(b), 0), time.size());
    brick_time_stats(time, s, own, w.series, range.width(), leaf, use);
    hand_over(res);
    if (remote()) {
      const auto bytes = std::as_bytes(std::span<const NodeAccum>(leaf));
      res.stats.assign(bytes.begin(), bytes.end());
      part->send(res);
    }
    report(progress, total_bytes);
  }

  // A level brick: quantized like a leaf (its statistics are the node's, merged from its leaves).
  void level(int j, Scratch& w, const ProgressFn& progress, std::int64_t total_bytes) {
    const Octree& o = tree.octree();
    const int steps = tree.time().steps();
    const BrickLattice l = o.lattice(o.brick_count() + j);
    w.series.resize(std::size_t(l.count()) * steps);
    levels.read_series(j, w.series);
    levels.discard(j);
    sanitize(w.series, range);
    quantize_padded(w.series, l, stored_brick_shape(o), steps, FastQuantizer(range), w.codes);
    BrickResult res;
    res.brick = o.brick_count() + j;
    put_codes(res.brick, w.codes, res);
    if (stencil.levels) {
      w.mask.resize(w.series.size());
      stencil.levels->read_series(j, w.mask);
      stencil.levels->discard(j);
      quantize_padded(w.mask, l, stored_brick_shape(o), steps, InsideFlag{}, w.flags);
      put_inside(res.brick, w.flags, res);
    }
    const int node = o.stored_brick_node(res.brick);
    if (o.stopped(node)) stopped_stats(node, l, w);
    hand_over(res);
    if (remote()) {
      const auto bytes = std::as_bytes(level_errors.subspan(std::size_t(j) * steps, steps));
      res.stats.assign(bytes.begin(), bytes.end());
      part->send(res);
    }
    report(progress, total_bytes);
  }

  // A stopped node of an adaptive octree is a leaf drawn from its level brick: its statistics
  // come from that brick's samples inside its own box, each weighing for the voxels it stands
  // for (own voxels / own samples), so that merging with finer siblings stays fair. w.series
  // holds the sanitized samples, w.mask the stencil's (with one).
  void stopped_stats(int node, const BrickLattice& l, Scratch& w) {
    const Octree& o = tree.octree();
    const TimeTree& time = tree.time();
    const int steps = time.steps();
    const Box& own_voxels = o.node(node).box;
    Box samples, own;
    for (int a = 0; a < 3; ++a) {
      samples.hi[a] = l.samples[a];
      const int f = l.factor[a];
      own.hi[a] = std::min(l.samples[a], (own_voxels.hi[a] - l.origin[a] + f - 1) / f);
    }
    std::span<const std::uint8_t> use;
    std::int64_t inside = own.count();
    if (stencil.levels) {
      const std::size_t per = std::size_t(samples.count());
      w.flags.assign(per, 0);
      for (int t = 0; t < steps; ++t)
        for (std::size_t i = 0; i < per; ++i)
          w.flags[i] |= w.mask[std::size_t(t) * per + i] >= 0.5f ? 1 : 0;
      use = w.flags;
      inside = 0;
      for (int z = 0; z < own.hi[2]; ++z)
        for (int y = 0; y < own.hi[1]; ++y)
          for (int x = 0; x < own.hi[0]; ++x)
            inside += w.flags[std::size_t(x + samples.hi[0] * (y + samples.hi[1] * z))];
    }
    const double weight = double(own_voxels.count()) / double(std::max<std::int64_t>(own.count(), 1));
    std::span<NodeAccum> leaf(acc.data() + tree.id(node, 0), time.size());
    brick_time_stats(time, samples, own, w.series, range.width(), leaf, use);
    for (NodeAccum& a : leaf) {
      a.moments.n *= weight;
      a.moments.m2 *= weight;
      a.cov_sum *= weight;
      a.voxels = std::int64_t(std::llround(double(a.voxels) * weight));
    }
    inside_voxels[std::size_t(o.node_brick(node))] = std::int64_t(std::llround(double(inside) * weight));
    // The histogram counts each sample as the voxels it stands for (rounded).
    std::vector<std::uint64_t> h(kHistogramBins, 0);
    add_histogram(w.series, stencil.levels ? std::span<const float>(w.mask) : std::span<const float>(),
                  samples, own, steps, range, h);
    const auto times = std::uint64_t(std::max<long long>(1, std::llround(weight)));
    for (int i = 0; i < kHistogramBins; ++i) w.hist[std::size_t(i)] += h[std::size_t(i)] * times;
  }

  bool remote() const { return part && part->rank() != 0; }
  bool collective() const { return ordered != nullptr; }
  void put_codes(int b, std::span<const std::uint16_t> codes, BrickResult& res) {
    if (remote() || collective())
      res.codes.assign(codes.begin(), codes.end());
    else
      writer->write_brick_series(b, codes);
  }
  void put_inside(int b, std::span<const std::uint8_t> flags, BrickResult& res) {
    if (remote() || collective())
      res.inside.assign(flags.begin(), flags.end());
    else
      writer->write_inside_series(b, flags);
  }
  // Collective writes: the brick's codes (and stencil) go to this rank's ordered writes; what
  // is sent to rank 0 is then only its statistics.
  void hand_over(BrickResult& res) {
    if (!collective()) return;
    const int ranks = part->ranks();
    ordered->put((res.brick - part->rank()) / ranks, std::exchange(res.codes, {}),
                 std::exchange(res.inside, {}));
  }

  // Rank 0: writes a brick another rank computed and takes its statistics. Throws Error when
  // the message does not fit the tree (ranks built from different inputs).
  void absorb(const BrickResult& r, const ProgressFn& progress, std::int64_t total_bytes) {
    const Octree& o = tree.octree();
    const int steps = tree.time().steps();
    const auto shape = stored_brick_shape(o);
    const std::size_t per = std::size_t(steps) * shape[0] * shape[1] * shape[2];
    const bool leaf = r.brick < o.brick_count();
    const std::size_t stats_bytes =
        leaf ? tree.time().size() * sizeof(NodeAccum) : std::size_t(steps) * sizeof(float);
    if (r.brick < 0 || r.brick >= o.stored_brick_count() || part->owns(r.brick) ||
        received[std::size_t(r.brick)]++ ||
        r.codes.size() != (collective() ? 0 : per) ||
        r.inside.size() != (stencil.leaves && !collective() ? per : 0) ||
        r.stats.size() != stats_bytes)
      throw Error("build: rank " + std::to_string(r.brick % part->ranks()) +
                  " sent brick " + std::to_string(r.brick) +
                  " twice or of another shape than rank 0's tree (do all ranks read the same "
                  "input?)");
    if (!collective()) {
      writer->write_brick_series(r.brick, r.codes);
      if (stencil.leaves) writer->write_inside_series(r.brick, r.inside);
    }
    if (leaf) {
      std::memcpy(acc.data() + tree.id(o.brick_node(r.brick), 0), r.stats.data(), stats_bytes);
      inside_voxels[std::size_t(r.brick)] = r.inside_voxels;
    } else {
      std::memcpy(level_errors.data() + std::size_t(r.brick - o.brick_count()) * steps,
                  r.stats.data(), stats_bytes);
    }
    report(progress, total_bytes);
  }

  void report(const ProgressFn& progress, std::int64_t total_bytes) {
    std::lock_guard lock(mutex);
    ++done;
    if (progress)
      progress(kPhaseBricks, total_bytes * done / tree.octree().stored_brick_count(), total_bytes);
  }

  // This process's stored bricks on `threads` workers; with a partition, rank 0 meanwhile
  // absorbs the others' bricks on one more thread, and the histogram is summed on rank 0.
  void run(int threads, const ProgressFn& progress, std::int64_t total_bytes) {
    const int bricks = tree.octree().brick_count();
    const int stored = tree.octree().stored_brick_count();
    const int ranks = part ? part->ranks() : 1, rank = part ? part->rank() : 0;
    const std::int64_t mine = part ? part->share(stored) : stored;  // b = rank + k·ranks
    std::vector<Scratch> workers(std::size_t(parallel_workers(mine, 1, threads)));
    // Before the receiver starts: what it accepts depends on whether the writes are collective.
    std::optional<OrderedWrites> writes;
    if (part && part->collective_io()) {
      writes.emplace(*writer, (stored + ranks - 1) / ranks, mine, rank, ranks,
                     std::int64_t(workers.size()));
      ordered = &*writes;
    }
    // Abandoned, not joined, when this process fails: it may wait for bricks never sent.
    BackgroundWorker receiver({}, WorkerExit::abandon);
    if (rank == 0 && stored > mine)
      receiver.submit([&, count = stored - mine](std::stop_token) {
        for (std::int64_t k = 0; k < count; ++k) absorb(part->receive(), progress, total_bytes);
      });
    parallel_for(mine, 1, threads, [&](int w, std::int64_t first, std::int64_t last) {
      for (auto k = first; k < last; ++k) {
        const std::int64_t b = rank + k * ranks;
        if (!tree.octree().brick_present(int(b)))  // below a stop (adaptive octrees): no data
          report(progress, total_bytes);
        else if (b < bricks)
          brick(int(b), workers[std::size_t(w)], progress, total_bytes);
        else
          level(int(b - bricks), workers[std::size_t(w)], progress, total_bytes);
      }
    });
    if (writes) writes->finish();
    receiver.wait();
    for (const Scratch& w : workers)
      for (int i = 0; i < kHistogramBins; ++i) histogram[i] += w.hist[i];
    if (part) part->sum_to_writer(histogram);
  }
};

}  // namespace

BrickPassResult run_brick_pass(const TspTree& tree, ScratchFile& scratch, ScratchFile& levels,
                               StencilScratch stencil, TspWriter* writer, ValueRange range,
                               std::vector<NodeAccum>& acc, std::span<float> level_errors,
                               BuildPartition* partition, int threads, const ProgressFn& progress,
                               std::int64_t total_bytes) {
  BrickPass pass(tree, scratch, levels, stencil, writer, range, acc, level_errors, partition);
  pass.run(threads, progress, total_bytes);
  return {std::move(pass.histogram), std::move(pass.inside_voxels)};
}

}  // namespace tsp::detail
