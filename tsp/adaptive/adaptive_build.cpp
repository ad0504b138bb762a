#include "tsp/adaptive/adaptive_build.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include "tsp/adaptive/adaptive_octree.h"
#include "tsp/adaptive/cell_lists.h"
#include "tsp/build/brick_pass.h"
#include "tsp/build/scratch_file.h"
#include "tsp/core/error.h"
#include "tsp/core/parallel_for.h"
#include "tsp/core/stopwatch.h"
#include "tsp/core/temp_output.h"
#include "tsp/store/tsp_layout.h"
#include "tsp/store/tsp_writer.h"
#include "tsp/tree/moments.h"
#include "tsp/tree/tsp_tree.h"
#include "tsp/voxelize/voxelizer.h"

namespace tsp {
namespace {

constexpr const char* kPhaseOctree = "octree";
constexpr const char* kPhaseSample = "voxelizing";

// The cells of m listed in cells as a mesh of their own (points renumbered in first use; map
// holds −1 for every point on entry and on return).
Mesh sub_mesh(const Mesh& m, const std::vector<std::int64_t>& cells, std::vector<std::int64_t>& map) {
  Mesh s;
  s.cell_values = m.cell_values;
  std::vector<std::int64_t> used;
  auto point = [&](std::int64_t p) {
    std::int64_t& k = map[std::size_t(p)];
    if (k < 0) {
      k = std::int64_t(used.size());
      used.push_back(p);
    }
    return k;
  };
  s.offsets.push_back(0);
  const bool faces = !m.face_start.empty();
  for (std::int64_t c : cells) {
    for (std::int64_t k = m.offsets[std::size_t(c)]; k < m.offsets[std::size_t(c) + 1]; ++k)
      s.connectivity.push_back(point(m.connectivity[std::size_t(k)]));
    s.offsets.push_back(std::int64_t(s.connectivity.size()));
    s.types.push_back(m.types[std::size_t(c)]);
    if (m.cell_values) s.values.push_back(m.values[std::size_t(c)]);
    if (!faces) continue;
    std::int64_t f = m.face_start[std::size_t(c)];
    if (f < 0) {
      s.face_start.push_back(-1);
      continue;
    }
    s.face_start.push_back(std::int64_t(s.faces.size()));
    const std::int64_t nf = m.faces[std::size_t(f++)];
    s.faces.push_back(nf);
    for (std::int64_t i = 0; i < nf; ++i) {
      const std::int64_t n = m.faces[std::size_t(f++)];
      s.faces.push_back(n);
      for (std::int64_t j = 0; j < n; ++j) s.faces.push_back(point(m.faces[std::size_t(f++)]));
    }
  }
  for (std::int64_t p : used) {
    for (int a = 0; a < 3; ++a) s.points.push_back(m.points[std::size_t(3 * p + a)]);
    if (!m.cell_values) s.values.push_back(m.values[std::size_t(p)]);
    map[std::size_t(p)] = -1;
  }
  return s;
}

// Trilinear value of lattice l's samples v at voxel coordinate x (clamped to the lattice).
double trilinear(const std::vector<float>& v, const BrickLattice& l, const std::array<int, 3>& x) {
  int i0[3];
  double w[3];
  for (int a = 0; a < 3; ++a) {
    const double u = std::clamp(double(x[a] - l.origin[a]) / l.factor[a], 0.0,
                                double(l.samples[a] - 1));
    i0[a] = std::min(int(u), std::max(l.samples[a] - 2, 0));
    w[a] = l.samples[a] > 1 ? u - i0[a] : 0.0;
  }
  const std::size_t sx = std::size_t(l.samples[0]), sxy = sx * std::size_t(l.samples[1]);
  double out = 0;
  for (int k = 0; k < 8; ++k) {
    double wk = 1;
    std::size_t idx = 0;
    for (int a = 0; a < 3; ++a) {
      const int hi = (k >> a) & 1;
      if (hi && l.samples[a] < 2) {
        wk = 0;
        break;
      }
      wk *= hi ? w[a] : 1 - w[a];
      idx += std::size_t(i0[a] + hi) * (a == 0 ? 1 : a == 1 ? sx : sxy);
    }
    if (wk != 0) out += wk * v[idx];
  }
  return out;
}

// Lattice indices of l's samples inside node box own (half-open), from 0.
Box own_samples(const BrickLattice& l, const Box& own) {
  Box b;
  for (int a = 0; a < 3; ++a)
    b.hi[a] = std::min(l.samples[a], (own.hi[a] - l.origin[a] + l.factor[a] - 1) / l.factor[a]);
  return b;
}

struct Sampler {
  MeshSource& source;
  const TspTree& tree;
  const VoxelGrid& grid;
  const AdaptiveOptions& options;
  const CellLists& lists;
  const MeshScan& scan;
  ScratchFile& leaves;
  ScratchFile& levels;
  ScratchFile& leaf_masks;
  ScratchFile& level_masks;
  std::span<float> level_errors;  // [level brick][step]

  struct Worker {
    std::vector<std::int64_t> map;
    std::vector<float> values, mask;
    std::vector<std::uint8_t> inside;
    // An inner node's children: their lattices, samples and inside fractions at this step.
    std::array<BrickLattice, 8> kid_lattices;
    std::array<std::vector<float>, 8> kid_values, kid_masks;
  };

  // The scratch file holding stored brick `brick`'s samples (mask: its inside fractions), and
  // the brick's index in it.
  std::pair<ScratchFile*, int> slot(int brick, bool mask) const {
    const int nb = tree.octree().brick_count();
    if (brick < nb) return {mask ? &leaf_masks : &leaves, brick};
    return {mask ? &level_masks : &levels, brick - nb};
  }
  void write(int brick, int t, std::span<const float> v, std::span<const float> m) {
    const auto [values, i] = slot(brick, false);
    values->write(i, t, v);
    slot(brick, true).first->write(i, t, m);
  }
  void read(int brick, int t, std::span<float> out, bool mask) const {
    const auto [file, i] = slot(brick, mask);
    file->read(i, t, out);
  }

  // An inner node's samples (and inside fractions) as its children's trilinear field at them:
  // its children cover its box, so its cells need not be sampled again (the level bricks of the
  // uniform build are likewise made from the finer field, there by a box filter).
  void from_children(int id, int t, const BrickLattice& l, Worker& w) const {
    const Octree& o = tree.octree();
    const std::array<int, 8>& kids = o.node(id).children;
    for (std::size_t k = 0; k < kids.size(); ++k) {
      if (kids[k] < 0) continue;
      w.kid_lattices[k] = o.lattice(o.node_brick(kids[k]));
      const std::size_t n = std::size_t(w.kid_lattices[k].count());
      w.kid_values[k].resize(n);
      w.kid_masks[k].resize(n);
      read(o.node_brick(kids[k]), t, w.kid_values[k], false);
      read(o.node_brick(kids[k]), t, w.kid_masks[k], true);
    }
    const Dims d = o.dims();
    std::size_t i = 0;
    for (int z = 0; z < l.samples[2]; ++z)
      for (int y = 0; y < l.samples[1]; ++y)
        for (int x = 0; x < l.samples[0]; ++x, ++i) {
          const std::array<int, 3> p{std::min(l.origin[0] + x * l.factor[0], d[0] - 1),
                                     std::min(l.origin[1] + y * l.factor[1], d[1] - 1),
                                     std::min(l.origin[2] + z * l.factor[2], d[2] - 1)};
          for (std::size_t k = 0; k < kids.size(); ++k) {
            if (kids[k] < 0) continue;
            const Box& b = o.node(kids[k]).box;  // its samples reach its shared upper layer
            if (p[0] < b.lo[0] || p[0] > b.hi[0] || p[1] < b.lo[1] || p[1] > b.hi[1] ||
                p[2] < b.lo[2] || p[2] > b.hi[2])
              continue;
            w.values[i] = float(trilinear(w.kid_values[k], w.kid_lattices[k], p));
            w.mask[i] = float(trilinear(w.kid_masks[k], w.kid_lattices[k], p));
            break;
          }
        }
  }

  // Node id's brick at step t from its own cells, and its level error against its children's.
  void node(int id, int t, const Mesh& mesh, Worker& w) {
    const Octree& o = tree.octree();
    const int brick = o.node_brick(id);
    const BrickLattice l = o.lattice(brick);
    const std::size_t n = std::size_t(l.count());
    w.values.assign(n, 0.f);
    w.mask.assign(n, 0.f);
    if (!o.node(id).is_leaf()) {
      from_children(id, t, l, w);
      write(brick, t, w.values, w.mask);
      level_error(id, t, l, w);
      return;
    }
    w.inside.assign(n, 0);
    const std::vector<std::int64_t> cells =
        lists.get(std::int64_t(id) * scan.list_steps() + scan.list_step(t));
    if (!cells.empty()) {
      const Mesh sub = sub_mesh(mesh, cells, w.map);
      VoxelGrid g;
      g.dims = Dims{l.samples[0], l.samples[1], l.samples[2]};
      for (int a = 0; a < 3; ++a) {
        g.origin[a] = grid.origin[a] + l.origin[a] * grid.spacing[a];
        g.spacing[a] = l.factor[a] * grid.spacing[a];
      }
      SampleOptions so = options.voxelize.sample;
      so.threads = 1;  // the nodes are the parallel work
      try {
        voxelize(sub, g, w.values, w.inside, so);
      } catch (const FormatError& e) {
        throw FormatError(source.describe() + ", step " + std::to_string(t) + ", octree node " +
                          std::to_string(id) + ": " + e.what());
      }
    }
    w.mask.assign(w.inside.begin(), w.inside.end());
    write(brick, t, w.values, w.mask);  // a leaf or a stopped node: level error 0
  }

  // Inner node id's level error at step t: its brick's samples w.values on lattice l against
  // its children's (w.kid_*, as from_children read them).
  void level_error(int id, int t, const BrickLattice& l, const Worker& w) {
    const Octree& o = tree.octree();
    const int brick = o.node_brick(id);
    // RMS of (this brick's trilinear reconstruction − each child's samples) over the child's own
    // samples, plus the child's own level error, weighted by the children's voxels.
    double sum = 0, weight = 0;
    const int steps = tree.time().steps();
    const std::array<int, 8>& kids = o.node(id).children;
    for (std::size_t k = 0; k < kids.size(); ++k) {
      const int c = kids[k];
      if (c < 0) continue;
      const int cb = o.node_brick(c);
      const BrickLattice& cl = w.kid_lattices[k];
      const std::vector<float>& child = w.kid_values[k];
      const Box own = own_samples(cl, o.node(c).box);
      double sq = 0;
      for (int z = 0; z < own.hi[2]; ++z)
        for (int y = 0; y < own.hi[1]; ++y)
          for (int x = 0; x < own.hi[0]; ++x) {
            const double r = trilinear(w.values, l,
                                       {cl.origin[0] + x * cl.factor[0], cl.origin[1] + y * cl.factor[1],
                                        cl.origin[2] + z * cl.factor[2]});
            const double d = r - child[std::size_t(x + cl.samples[0] * (y + cl.samples[1] * z))];
            sq += d * d;
          }
      const double mean_sq = own.count() > 0 ? sq / double(own.count()) : 0;
      const double child_err = o.node(c).is_leaf() && !o.stopped(c)
                                   ? 0.0
                                   : level_errors[std::size_t(cb - o.brick_count()) * steps + t];
      const double v = double(o.node(c).box.count());
      sum += v * (mean_sq + child_err * child_err);
      weight += v;
    }
    level_errors[std::size_t(brick - o.brick_count()) * steps + t] =
        float(weight > 0 ? std::sqrt(sum / weight) : 0.0);
  }

  // Every reachable node at every step, deepest level first (a node's level error reads its
  // children's samples), one step's mesh in memory at a time: the last step first, from the
  // scan's mesh `last`.
  void run(Mesh last, const ProgressFn& progress, int threads) {
    const Octree& o = tree.octree();
    std::vector<std::vector<int>> by_level(std::size_t(o.depth()) + 1);
    int total = 0;
    for (int id = 0; id < o.size(); ++id)
      if (o.reachable(id)) {
        by_level[std::size_t(o.node(id).level)].push_back(id);
        ++total;
      }
    const int steps = tree.time().steps();
    for (int t = steps - 1, done_steps = 0; t >= 0; --t, ++done_steps) {
      Mesh mesh;
      if (t == steps - 1) {
        mesh = std::move(last);
      } else {
        mesh = source.read_step(t);
        prepare_mesh(mesh, options.voxelize.cell_data);
      }
      std::vector<Worker> workers(std::size_t(resolve_threads(threads)));
      for (Worker& w : workers) w.map.assign(std::size_t(mesh.point_count()), -1);
      int done = 0;
      for (int level = o.depth(); level >= 0; --level) {
        const std::vector<int>& ids = by_level[std::size_t(level)];
        parallel_for(std::int64_t(ids.size()), 1, threads, [&](int wi, std::int64_t b, std::int64_t e) {
          for (std::int64_t k = b; k < e; ++k) node(ids[std::size_t(k)], t, mesh, workers[std::size_t(wi)]);
        });
        done += int(ids.size());
        if (progress) progress(kPhaseSample, std::int64_t(done_steps) * total + done, std::int64_t(steps) * total);
      }
    }
  }
};

}  // namespace

AdaptiveReport build_adaptive_tsp(MeshSource& source, const std::string& out_path,
                                  const AdaptiveOptions& options) {
  const Stopwatch watch;
  if (!std::isfinite(options.error) || options.error < 0)
    throw UsageError("--octree-error " + std::to_string(options.error) +
                     ": expected a finite threshold >= 0");
  if (out_path.empty()) throw UsageError("no output file given (-o)");
  if (options.build.range) {
    const ValueRange r = *options.build.range;
    if (!std::isfinite(r.lo) || !std::isfinite(r.hi) || !(r.lo < r.hi))
      throw UsageError("--range: expected finite LO < HI");
  }
  const InputGuard inputs(source.files());
  TempOutput out(out_path, options.build.output_links);
  const std::string dir = output_directory(out_path);
  const int steps = source.steps();
  if (steps < 1) throw FormatError(source.describe() + ": no time steps");
  const std::vector<double> times = source.times();
  check_step_times(source.describe(), times);

  AdaptiveReport rep;
  if (options.build.progress) options.build.progress(kPhaseOctree, 0, 1);
  MeshScan scan = scan_mesh(source, options.voxelize.cell_data, dir);
  for (int a = 0; a < 3; ++a)
    if (!(scan.bounds.hi[a] - scan.bounds.lo[a] > 0))
      throw FormatError(source.describe() + ": the mesh is flat along " +
                        std::string(1, char('x' + a)) + "; a surface has no inside to voxelize");
  const VoxelGrid grid = choose_grid(scan.bounds, scan.median_cell, options.voxelize,
                                     kMaxAdaptiveSamples);
  rep.dims = grid.dims;
  const int brick = options.build.brick_size > 0 ? options.build.brick_size
                                                 : default_brick_size(grid.dims);
  TspTree tree(grid.dims, steps, brick);
  rep.complete_nodes = tree.octree().size();
  rep.threshold = options.relative ? options.error * scan.data.width() : options.error;
  CellLists lists(dir, std::int64_t(tree.octree().size()) * scan.list_steps(), "the octree's cell lists");
  const Subdivision sub = subdivide(tree.octree(), grid, scan, rep.threshold, lists);
  tree.stop_at(sub.stopped);
  rep.nodes = sub.reachable;
  rep.stopped = sub.stopped_count;
  rep.cell_list_bytes = lists.bytes();
  rep.octree_seconds = watch.seconds();

  const Octree& o = tree.octree();
  const int nb = o.brick_count(), nl = o.level_brick_count();
  const auto shape = stored_brick_shape(o);
  const std::int64_t per_brick = std::int64_t(shape[0]) * shape[1] * shape[2] * steps * 2;
  std::vector<std::int64_t> leaf_samples(std::size_t(nb), 0), level_samples(std::size_t(nl), 0);
  for (int i = 0; i < o.stored_brick_count(); ++i) {
    rep.complete_brick_bytes += per_brick;
    if (!o.brick_present(i)) continue;
    rep.brick_bytes += per_brick;
    (i < nb ? leaf_samples[std::size_t(i)] : level_samples[std::size_t(i - nb)]) =
        o.lattice(i).count();
  }
  ScratchFile leaves(dir, leaf_samples, steps), levels(dir, level_samples, steps);
  ScratchFile leaf_masks(dir, leaf_samples, steps), level_masks(dir, level_samples, steps);
  const int threads = resolve_threads(options.build.threads);
  Sampler{source, tree, grid, options, lists, scan, leaves, levels, leaf_masks, level_masks,
          tree.level_errors()}
      .run(std::move(scan.last), options.build.progress, threads);
  rep.voxelize_seconds = watch.seconds() - rep.octree_seconds;

  BuildReport& br = rep.build;
  br.source_bytes = grid.dims.count() * steps * std::int64_t(sizeof(float));
  br.nonfinite_count = scan.nonfinite;
  br.data_range = scan.data;
  br.value_range = options.build.range.value_or(scan.data);
  tree.set_value_range(br.value_range);
  tree.set_inside_fractions(std::vector<float>(std::size_t(o.size()), 1.f));  // filled below
  std::vector<NodeAccum> acc(std::size_t(tree.size()));
  TspWriter writer(out.tmp(), tree, 0, options.build.deflate);
  const detail::BrickPassResult pass = detail::run_brick_pass(
      tree, leaves, levels, {&leaf_masks, &level_masks}, &writer, br.value_range, acc,
      tree.level_errors(), nullptr, threads, options.build.progress, br.source_bytes);
  // Inner nodes merge their children, bottom-up; nodes below a stop take the stopped node's.
  const int nt = tree.time().size();
  std::vector<std::int64_t> in(std::size_t(o.size()), 0), all(std::size_t(o.size()), 0);
  for (int i = o.size() - 1; i >= 0; --i) {
    if (!o.reachable(i)) continue;
    const OctreeNode& n = o.node(i);
    if (n.is_leaf()) {
      in[std::size_t(i)] = pass.inside_voxels[std::size_t(n.brick)];
      all[std::size_t(i)] = n.box.count();
      continue;
    }
    for (int c : n.children) {
      if (c < 0) continue;
      for (int tau = 0; tau < nt; ++tau) acc[std::size_t(tree.id(i, tau))].merge(acc[std::size_t(tree.id(c, tau))]);
      in[std::size_t(i)] += in[std::size_t(c)];
      all[std::size_t(i)] += all[std::size_t(c)];
    }
  }
  std::vector<float> fraction(std::size_t(o.size()), 0.f);
  for (int i = 0; i < o.size(); ++i) {
    const int from = o.reachable(i) ? i : o.stop_above(i);
    if (all[std::size_t(from)] > 0)
      fraction[std::size_t(i)] = float(double(in[std::size_t(from)]) / double(all[std::size_t(from)]));
    for (int tau = 0; tau < nt; ++tau)
      tree.stats(tree.id(i, tau)) = acc[std::size_t(tree.id(from, tau))].finish(br.value_range.width());
  }
  tree.set_inside_fractions(std::move(fraction));
  TspMetadata meta;
  meta.source = source.describe() + ", adaptive octree over " + to_string(grid.dims) + " (E = " +
                std::to_string(rep.threshold) + ")";
  meta.field = options.build.field_name.empty() ? source.field() : options.build.field_name;
  meta.data_range = br.data_range;
  meta.nonfinite_count = br.nonfinite_count;
  meta.histogram = pass.histogram;
  meta.created_by = "tspplay " TSPPLAY_VERSION;
  meta.origin = grid.origin;
  meta.spacing = grid.spacing;
  meta.times = times.size() == std::size_t(steps) ? times : std::vector<double>{};
  writer.finish(tree, meta);
  out.commit();
  br.seconds = watch.seconds();
  return rep;
}

}  // namespace tsp
