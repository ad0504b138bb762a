#include "tsp/build/build.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <deque>
#include <functional>
#include <limits>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "tsp/build/brick_pass.h"
#include "tsp/build/level_filter.h"
#include "tsp/build/scratch_file.h"
#include "tsp/build/slab_prefetcher.h"
#include "tsp/core/background_worker.h"
#include "tsp/core/error.h"
#include "tsp/core/geometry.h"
#include "tsp/core/parallel_for.h"
#include "tsp/core/stopwatch.h"
#include "tsp/core/temp_output.h"
#include "tsp/store/tsp_file.h"
#include "tsp/store/tsp_layout.h"
#include "tsp/store/tsp_writer.h"
#include "tsp/tree/tsp_tree.h"

namespace tsp {

namespace {

constexpr const char* kPhaseRead = "reading";
// Pass 1 reads a step in slabs of a quarter of a brick layer: a layer's planes are held until its
// bricks are cut out, and the slabs before and after it are being read and scanned.
constexpr int kSlabsPerLayer = 4;

// Finite extremes and non-finite count of the input, over every voxel of every step.
struct InputScan {
  float lo = std::numeric_limits<float>::infinity();
  float hi = -std::numeric_limits<float>::infinity();
  std::int64_t nonfinite = 0;
  // Only inside voxels (mask ≠ 0) count when the step has a stencil (a mask).
  void add(std::span<const float> v, std::span<const float> mask) {
    float l = lo, h = hi;
    std::int64_t bad = 0;
    for (std::size_t i = 0; i < v.size(); ++i) {
      const float x = v[i];
      if (!mask.empty() && mask[i] == 0) continue;
      if (std::isfinite(x)) {
        l = std::min(l, x);
        h = std::max(h, x);
      } else {
        ++bad;
      }
    }
    lo = l;
    hi = h;
    nonfinite += bad;
  }
  ValueRange range() const { return lo <= hi ? ValueRange{lo, hi} : ValueRange{0, 0}; }
};


// Planes per slab of pass 1: a quarter of a brick layer, rounded up to a multiple of how the
// input is stored (an HDF5 chunk's depth), so that no chunk is read (and decompressed) twice.
int slab_planes(const VolumeSource& source, const Octree& octree) {
  const int planes = std::max(1, octree.brick_cells(2) / kSlabsPerLayer);
  const int align = std::clamp(source.slab_alignment(), 0, octree.dims().z);
  return align > 1 ? (planes + align - 1) / align * align : planes;
}

// One process's reading side of pass 1, a step at a time: each slab of planes is held while a
// brick or a level stream still needs it; each leaf brick's samples are copied out as soon as
// the planes it covers are in, each level brick is filtered (and its residual summed) by a
// LevelStream fed the same planes in z order, so only the planes a window or a brick still
// needs are held, never the whole step. What is done goes to `deliver`.
class StepScatter {
 public:
  /// Where a brick's samples (or stencil flags) at a step go: stored brick index, step, mask or
  /// values, the samples, a level brick's residual.
  using Deliver =
      std::function<void(int stored, int t, bool is_mask, const std::vector<float>& v, float r)>;

  StepScatter(const Octree& octree, bool masks, const std::optional<ValueRange>& clamp,
              Deliver deliver)
      : octree_(octree), d_(octree.dims()), n_(octree.brick_count()),
        nl_(octree.level_brick_count()), deliver_(std::move(deliver)),
        samples_(static_cast<std::size_t>(n_)), scattered_(static_cast<std::size_t>(n_)),
        bricks_(kWorkers) {
    // One stream per level brick for its values, one more for its stencil.
    for (int j = 0; j < nl_; ++j) {
      const BrickLattice l = octree.lattice(n_ + j);
      values_.emplace_back(d_, l, octree.node(octree.stored_brick_node(n_ + j)).box, clamp);
      if (masks) masks_.emplace_back(d_, l, std::nullopt, std::nullopt);
    }
    for (int b = 0; b < n_; ++b) samples_[std::size_t(b)] = octree.brick_samples(b);
  }

  /// Step t, from prefetch's slabs (the next ones it holds are this step's, in z order), with
  /// `leaves_masked` when leaf bricks carry a stencil. at_plane(end) after each slab.
  void step(int t, SlabPrefetcher& prefetch, bool leaves_masked,
            const std::function<void(int end)>& at_plane) {
    for (LevelStream& s : values_) s.restart();
    for (LevelStream& s : masks_) s.restart();
    std::fill(scattered_.begin(), scattered_.end(), 0);
    held_.clear();
    for (int end = 0; end < d_.z;) {
      Slab slab = prefetch.next();
      assert(slab.step == t && slab.z0 == end);
      end = slab.z1;
      held_.push_back(std::move(slab));
      ready_.clear();  // this round's work: leaf bricks, then level streams (j + n)
      for (int b = 0; b < n_; ++b)
        if (!scattered_[std::size_t(b)] && samples_[std::size_t(b)].hi[2] <= end) {
          scattered_[std::size_t(b)] = 1;
          ready_.push_back(b);
        }
      for (int j = 0; j < nl_; ++j)
        if (!values_[std::size_t(j)].done() ||
            (!masks_.empty() && !masks_[std::size_t(j)].done()))
          ready_.push_back(n_ + j);
      // Copying into the page cache is kernel time that parallelises: two workers split each
      // slab's work (pwrite at fixed offsets needs no ordering).
      parallel_for(kWorkers, 1, kWorkers, [&](int w, std::int64_t first, std::int64_t) {
        for (auto k = std::size_t(first); k < ready_.size(); k += kWorkers)
          work(t, ready_[k], end, leaves_masked, bricks_[std::size_t(w)]);
      });
      drop_slabs(end);
      if (at_plane) at_plane(end);
    }
    assert(std::all_of(values_.begin(), values_.end(), [](auto& s) { return s.done(); }));
  }

 private:
  static constexpr int kWorkers = 2;
  const Octree& octree_;
  const Dims d_;
  const int n_, nl_;
  Deliver deliver_;
  std::vector<Box> samples_;  // each leaf brick's samples, for the planes
  std::vector<LevelStream> values_, masks_;
  std::vector<char> scattered_;
  std::vector<int> ready_;
  std::vector<std::vector<float>> bricks_;  // per worker
  std::deque<Slab> held_;  // the step's slabs still needed, in z order

  const float* plane(int z, bool mask) const {
    for (const Slab& s : held_)
      if (z >= s.z0 && z < s.z1) return mask ? s.mask_plane(z) : s.plane(z);
    assert(false && "a plane that is no longer held");
    return nullptr;
  }

  // Leaf brick b's samples (or stencil flags) at step t, copied out of the held planes.
  void scatter(int t, int b, bool is_mask, std::vector<float>& brick) {
    const Box& s = samples_[std::size_t(b)];
    brick.resize(std::size_t(s.count()));
    float* out = brick.data();
    const std::size_t row = std::size_t(s.size(0));
    for (int z = s.lo[2]; z < s.hi[2]; ++z) {
      const float* p = plane(z, is_mask);
      for (int y = s.lo[1]; y < s.hi[1]; ++y, out += row)
        std::memcpy(out, p + s.lo[0] + std::int64_t(d_.x) * y, row * sizeof(float));
    }
    deliver_(b, t, is_mask, brick, 0.f);
  }

  // One item of a round: leaf brick i, or level brick i − n fed the planes up to end.
  void work(int t, int i, int end, bool leaves_masked, std::vector<float>& brick) {
    if (i < n_) {
      scatter(t, i, false, brick);
      if (leaves_masked) scatter(t, i, true, brick);
      return;
    }
    const LevelStream::PlaneFn value_plane = [this](int z) { return plane(z, false); };
    LevelStream& v = values_[std::size_t(i - n_)];
    if (!v.done()) {
      v.feed(value_plane, end);
      if (v.done()) {
        deliver_(i, t, false, v.samples(), float(v.residual()));
        v.release();
      }
    }
    if (masks_.empty()) return;
    LevelStream& m = masks_[std::size_t(i - n_)];
    if (m.done()) return;
    m.feed([this](int z) { return plane(z, true); }, end);
    if (m.done()) {
      deliver_(i, t, true, m.samples(), 0.f);
      m.release();
    }
  }

  // Drops the slabs below every plane a brick or stream still needs.
  void drop_slabs(int end) {
    int keep = end;
    for (int b = 0; b < n_; ++b)
      if (!scattered_[std::size_t(b)]) keep = std::min(keep, samples_[std::size_t(b)].lo[2]);
    for (const LevelStream& s : values_) keep = std::min(keep, s.needs_from());
    for (const LevelStream& s : masks_) keep = std::min(keep, s.needs_from());
    while (!held_.empty() && held_.front().z1 <= keep) held_.pop_front();
  }
};

// Pass 1: every step once, in order, read in slabs of slab_planes() planes (or whole, where the
// source cannot read part of a step), scattered by a StepScatter: the leaf bricks' samples go
// to their place in the scratch file, the level bricks to levels, their residuals to
// level_errors ([level brick][step]). With a partition, this process reads its steps (t mod
// ranks = rank) and sends each other process's bricks at those steps to it, while a receiving
// thread stores what the others send of this process's bricks; the scans are then combined, so
// every process returns the scan of the whole input.
InputScan scatter_steps(VolumeSource& source, const Octree& octree, ScratchFile& scratch,
                        ScratchFile& levels, detail::StencilScratch stencil,
                        std::span<float> level_errors, const std::optional<ValueRange>& clamp,
                        BuildPartition* part, const ProgressFn& progress,
                        std::int64_t total_bytes) {
  const Dims d = octree.dims();
  const int steps = source.steps(), n = octree.brick_count(), nl = octree.level_brick_count();
  const int ranks = part ? part->ranks() : 1, rank = part ? part->rank() : 0;
  const std::int64_t plane_bytes = std::int64_t(d.x) * d.y * std::int64_t(sizeof(float));
  // A brick's samples (or stencil flags) at a step, into this process's scratch files.
  auto store = [&](int stored, int t, bool is_mask, std::span<const float> v, float residual) {
    if (stored < n) {
      (is_mask ? *stencil.leaves : scratch).write(stored, t, v);
      return;
    }
    const int j = stored - n;
    (is_mask ? *stencil.levels : levels).write(j, t, v);
    if (!is_mask) level_errors[std::size_t(j) * steps + t] = residual;
  };
  // ... or to the process that owns the brick.
  auto deliver = [&](int stored, int t, bool is_mask, const std::vector<float>& v,
                     float residual) {
    if (!part || part->owns(stored))
      store(stored, t, is_mask, v, residual);
    else
      part->send_samples({stored, t, is_mask, residual, {}}, v);
  };
  // What the other processes read of this process's bricks (each of its stored bricks at each
  // step it does not read, values and stencil), stored as it arrives.
  const std::int64_t expected = part ? part->share(n + nl) * (steps - part->share(steps)) *
                                           (stencil.leaves ? 2 : 1)
                                     : 0;
  // Received on a thread of its own while this process reads; abandoned, not joined, when this
  // process fails (it may wait for samples never sent: tspplay-mpi then aborts the job).
  BackgroundWorker receiver({}, WorkerExit::abandon);
  if (expected > 0)
    receiver.submit([&](std::stop_token) {
      for (std::int64_t k = 0; k < expected; ++k) {
        const StepSamples m = part->receive_samples();
        if (m.brick < 0 || m.brick >= n + nl || !part->owns(m.brick) || m.step < 0 ||
            m.step >= steps || part->reads(m.step) || (m.stencil && !stencil.leaves) ||
            std::int64_t(m.samples.size()) != octree.lattice(m.brick).count())
          throw Error("build: a rank sent samples of brick " + std::to_string(m.brick) +
                      " at step " + std::to_string(m.step) + " that rank " +
                      std::to_string(rank) + " does not expect (do all ranks read the same input?)");
        store(m.brick, m.step, m.stencil, m.samples, m.residual);
      }
    });
  InputScan scan;
  {
    // The reader thread also scans each slab, which balances the threads of this pass.
    SlabPrefetcher prefetch(
        source, slab_planes(source, octree),
        [&scan](const Slab& s) {
          const std::size_t count = std::size_t((s.z1 - s.z0) * s.plane_size);
          scan.add(std::span(s.plane(s.z0), count),
                   s.mask_plane(s.z0) ? std::span(s.mask_plane(s.z0), count)
                                      : std::span<const float>());
        },
        rank, ranks);
    StepScatter scatter(octree, stencil.levels != nullptr, clamp, deliver);
    for (int t = rank; t < steps; t += ranks)
      scatter.step(t, prefetch, stencil.leaves != nullptr, [&](int end) {
        if (progress)
          progress(kPhaseRead, (std::int64_t(t) * d.z + end) * plane_bytes, total_bytes);
      });
  }
  receiver.wait();
  if (part) part->combine_scan(scan.lo, scan.hi, scan.nonfinite);
  return scan;
}

// Internal octree nodes combine their children's sums per time node, bottom-up.
void combine_octree(const TspTree& tree, std::vector<NodeAccum>& acc) {
  const Octree& o = tree.octree();
  const int nt = tree.time().size();
  for (int i = o.size() - 1; i >= 0; --i) {
    if (o.node(i).is_leaf()) continue;
    for (int c : o.node(i).children) {
      if (c < 0) continue;
      for (int t = 0; t < nt; ++t) acc[tree.id(i, t)].merge(acc[tree.id(c, t)]);
    }
  }
}

// Per octree node, the fraction of its own voxels inside the data, from the leaves' counts.
std::vector<float> inside_fractions(const Octree& o, const std::vector<std::int64_t>& leaf_inside) {
  std::vector<std::int64_t> in(std::size_t(o.size()), 0), all(std::size_t(o.size()), 0);
  for (int i = o.size() - 1; i >= 0; --i) {
    const OctreeNode& n = o.node(i);
    if (n.is_leaf()) {
      in[std::size_t(i)] = leaf_inside[std::size_t(n.brick)];
      all[std::size_t(i)] = o.brick_box(n.brick).count();
      continue;
    }
    for (int c : n.children) {
      if (c < 0) continue;
      in[std::size_t(i)] += in[std::size_t(c)];
      all[std::size_t(i)] += all[std::size_t(c)];
    }
  }
  std::vector<float> f(in.size());
  for (std::size_t i = 0; i < f.size(); ++i)
    f[i] = all[i] > 0 ? float(double(in[i]) / double(all[i])) : 0.f;
  return f;
}

ValueRange checked_range(const std::optional<ValueRange>& r, ValueRange data) {
  if (!r) return data;
  if (!std::isfinite(r->lo) || !std::isfinite(r->hi) || !(r->lo < r->hi) ||
      !std::isfinite(r->width()))
    throw UsageError("--range " + std::to_string(r->lo) + ":" + std::to_string(r->hi) +
                     ": expected finite LO < HI whose width HI - LO is finite");
  return *r;
}

}  // namespace

namespace {

// Ranks other than 0 of a partitioned build own no output: they compute bricks and send them
// to rank 0, or write them into rank 0's temporary with collective writes.
bool writes_nothing(const BuildOptions& options) {
  return options.partition && options.partition->rank() != 0;
}

// Options checked before any work. Throws UsageError.
void check_options(const std::string& out_path, const BuildOptions& options) {
  if (options.range) checked_range(options.range, {});  // reject a bad range before any work
  if (options.deflate < 0 || options.deflate > 9)
    throw UsageError("--compress deflate:" + std::to_string(options.deflate) +
                     ": expected a level 1..9");
  if (options.threads < 0)
    throw UsageError("--threads " + std::to_string(options.threads) + ": expected 0 or more");
  if (out_path.empty()) throw UsageError("no output file given (-o)");
  if (options.spacing)
    if (const std::string why = spacing_problem({0, 0, 0}, *options.spacing); !why.empty())
      throw UsageError("--spacing: expected three positive voxel sizes that can be drawn: " + why);
  if (options.origin)
    if (const std::string why = spacing_problem(*options.origin, {1, 1, 1}); !why.empty())
      throw UsageError("--origin: expected three finite coordinates: " + why);
}

// The grid's origin and spacing as the file will hold them: the options' or the source's,
// refused naming the source when they cannot be drawn. Throws FormatError.
std::pair<std::array<double, 3>, std::array<double, 3>> checked_grid(const VolumeSource& source,
                                                                      const BuildOptions& o) {
  const std::array<double, 3> origin = o.origin.value_or(source.origin());
  const std::array<double, 3> spacing = o.spacing.value_or(source.spacing());
  if (const std::string why = spacing_problem(origin, spacing); !why.empty())
    throw FormatError(source.describe() + ": its grid's origin (" + std::to_string(origin[0]) +
                      ", " + std::to_string(origin[1]) + ", " + std::to_string(origin[2]) +
                      ") or voxel spacing cannot be drawn: " + why +
                      " (give --spacing DX,DY,DZ and --origin X,Y,Z)");
  return {origin, spacing};
}

// Builds one field of source into the temporary output out (field_index 0: the file's root,
// created; K ≥ 1: the group fields/K of the file field 0 was written to), with scratch files in
// scratch_dir. Ranks other than 0 of a partitioned build have no out (null): they compute
// their bricks and hand them to rank 0 (or, with collective writes, write them themselves).
BuildReport build_field(VolumeSource& source, const TempOutput* out,
                        const std::string& scratch_dir, int field_index,
                        const BuildOptions& options) {
  const Stopwatch watch;
  const Dims dims = source.dims();
  const int steps = source.steps();
  if (steps < 1) throw FormatError(source.describe() + ": no time steps");
  (void)checked_grid(source, options);  // before any work, as the times below
  // The .tsp reader refuses non-finite times: refuse them here, naming the input, before any
  // work (a build that wrote them would replace a good output with one nothing can read).
  const std::vector<double> times = source.times();
  check_step_times(source.describe(), times);
  TspTree tree(dims, steps, options.brick_size);
  const Octree& o = tree.octree();

  BuildReport report;
  report.source_bytes = dims.count() * steps * std::int64_t(sizeof(float));

  BuildPartition* part = options.partition;
  const auto mine = [part](std::int64_t b) { return !part || part->owns(b); };
  std::vector<std::int64_t> samples(o.brick_count());  // none for other ranks' bricks
  for (int b = 0; b < o.brick_count(); ++b) samples[b] = mine(b) ? o.brick_samples(b).count() : 0;
  ScratchFile scratch(scratch_dir, samples, steps);
  std::vector<std::int64_t> level_samples(o.level_brick_count());
  for (int j = 0; j < o.level_brick_count(); ++j)
    level_samples[j] = mine(o.brick_count() + j) ? o.lattice(o.brick_count() + j).count() : 0;
  ScratchFile levels(scratch_dir, level_samples, steps);
  std::optional<ScratchFile> leaf_masks, level_masks;
  detail::StencilScratch stencil;
  if (source.has_stencil()) {
    leaf_masks.emplace(scratch_dir, samples, steps);
    level_masks.emplace(scratch_dir, level_samples, steps);
    stencil = {&*leaf_masks, &*level_masks};
    tree.set_inside_fractions(std::vector<float>(std::size_t(o.size()), 1.f));  // filled below
  }
  InputScan scan = scatter_steps(source, o, scratch, levels, stencil, tree.level_errors(),
                                 options.range, part, options.progress, report.source_bytes);
  report.data_range = scan.range();
  report.nonfinite_count = scan.nonfinite;
  report.value_range = checked_range(options.range, report.data_range);
  tree.set_value_range(report.value_range);

  std::vector<NodeAccum> acc(tree.size());
  TspMetadata meta;
  const int threads = resolve_threads(options.threads);
  CollectiveIo* io = part ? part->collective_io() : nullptr;
  if (!out && !io) {  // a rank other than 0: its bricks go to rank 0
    detail::run_brick_pass(tree, scratch, levels, stencil, nullptr, report.value_range, acc,
                           tree.level_errors(), part, threads, options.progress,
                           report.source_bytes);
    report.seconds = watch.seconds();
    return report;
  }
  {
    // With collective writes every rank opens rank 0's temporary and writes its own bricks;
    // rank 0 then finishes the file alone.
    const std::string tmp = io ? part->broadcast_path(out ? out->tmp() : "") : out->tmp();
    TspWriter writer(tmp, tree, field_index, options.deflate, io);
    const detail::BrickPassResult pass = detail::run_brick_pass(
        tree, scratch, levels, stencil, &writer, report.value_range, acc, tree.level_errors(), part,
        threads, options.progress, report.source_bytes);
    if (io) writer.end_collective(out != nullptr);
    if (!out) {
      report.seconds = watch.seconds();
      return report;
    }
    combine_octree(tree, acc);
    if (stencil.leaves) tree.set_inside_fractions(inside_fractions(o, pass.inside_voxels));
    for (int i = 0; i < tree.size(); ++i) tree.stats(i) = acc[i].finish(report.value_range.width());
    meta.source = source.describe();
    meta.field = options.field_name.empty() ? source.field() : options.field_name;  // (picked: its own name)
    meta.data_range = report.data_range;
    meta.nonfinite_count = report.nonfinite_count;
    meta.histogram = pass.histogram;
    meta.created_by = "tspplay " TSPPLAY_VERSION;
    std::tie(meta.origin, meta.spacing) = checked_grid(source, options);
    meta.times = source.times();
    if (meta.times.size() != std::size_t(steps)) meta.times.clear();  // a reader's slip: none
    if (!meta.times.empty()) meta.time_units = source.time_units();
    meta.build_ranks = part ? part->ranks() : 1;
    writer.finish(tree, meta);
  }
  report.seconds = watch.seconds();
  return report;
}

}  // namespace

void check_step_times(const std::string& what, const std::vector<double>& times) {
  for (std::size_t t = 0; t < times.size(); ++t)
    if (!std::isfinite(times[t]))
      throw FormatError(what + ": the time of step " + std::to_string(t) + " is " +
                        std::to_string(times[t]) + "; step times must be finite numbers");
}

BuildReport build_tsp_file(VolumeSource& source, const std::string& out_path,
                           const BuildOptions& options) {
  check_options(out_path, options);
  const InputGuard inputs(source.files());
  std::optional<TempOutput> out;
  if (!writes_nothing(options)) out.emplace(out_path, options.output_links);
  BuildReport r =
      build_field(source, out ? &*out : nullptr, output_directory(out_path), 0, options);
  if (out) out->commit();
  return r;
}

std::vector<BuildReport> build_tsp_fields(const FieldSourceFn& open_field,
                                          const std::vector<std::string>& fields,
                                          const std::string& out_path,
                                          const BuildOptions& options) {
  check_options(out_path, options);
  if (fields.empty()) throw UsageError("--field: no field named");
  // Checked before any field is read (a limit on the file's list, not on opening the input).
  if (fields.size() > std::size_t(kMaxBuildFields))
    throw UsageError("--field: " + std::to_string(fields.size()) + " fields named; one .tsp file "
                     "holds at most " + std::to_string(kMaxBuildFields) +
                     " (build the others into another file)");
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (fields[i].empty() || fields[i].find('\n') != std::string::npos)
      throw UsageError("--field: field " + std::to_string(i + 1) +
                       " of the list is empty or holds a line break");
    for (std::size_t j = 0; j < i; ++j)
      if (fields[i] == fields[j])
        throw UsageError("--field: the field '" + fields[i] + "' is named twice");
  }
  std::vector<BuildReport> reports;
  InputGuard inputs;
  std::optional<TempOutput> out;
  int steps0 = 0;
  for (std::size_t k = 0; k < fields.size(); ++k) {
    std::unique_ptr<VolumeSource> source = open_field(fields[k]);
    if (k == 0) {
      for (const std::string& f : source->files()) inputs.add(f);
      if (!writes_nothing(options)) out.emplace(out_path, options.output_links);
      steps0 = source->steps();
    } else if (source->steps() != steps0) {
      throw FormatError(source->describe() + ": field " + fields[k] + " has " +
                        std::to_string(source->steps()) + " steps, the first field " + fields[0] +
                        " " + std::to_string(steps0) +
                        " (the fields of one .tsp play over the same steps)");
    }
    BuildOptions o = options;
    o.field_name = fields[k];
    if (options.progress && fields.size() > 1) {
      const std::string tag = fields[k] + " (" + std::to_string(k + 1) + "/" +
                              std::to_string(fields.size()) + ") ";
      o.progress = [tag, &options](const std::string& phase, std::int64_t done, std::int64_t total) {
        options.progress(tag + phase, done, total);
      };
    }
    reports.push_back(
        build_field(*source, out ? &*out : nullptr, output_directory(out_path), int(k), o));
  }
  if (!out) return reports;
  if (fields.size() > 1) TspWriter::write_field_list(out->tmp(), fields);
  out->commit();
  return reports;
}

int default_brick_size(Dims dims) {
  constexpr int kMin = 8, kMax = 64;
  const double quarter = std::max({dims.x, dims.y, dims.z}) / 4.0;
  int b = kMin;
  while (b < kMax && std::abs(std::log2(double(2 * b)) - std::log2(quarter)) <
                         std::abs(std::log2(double(b)) - std::log2(quarter)))
    b *= 2;
  return b;
}

}  // namespace tsp
