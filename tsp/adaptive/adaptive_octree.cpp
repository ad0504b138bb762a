#include "tsp/adaptive/adaptive_octree.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "tsp/core/error.h"
#include "tsp/voxelize/tetrahedra.h"

namespace tsp {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// Box of cell c's points (its connectivity; a polyhedron's lists its points too).
void cell_box(const Mesh& m, std::int64_t c, float lo[3], float hi[3]) {
  for (int a = 0; a < 3; ++a) {
    lo[a] = kInf;
    hi[a] = -kInf;
  }
  for (std::int64_t k = m.offsets[std::size_t(c)]; k < m.offsets[std::size_t(c) + 1]; ++k) {
    const double* p = m.points.data() + 3 * m.connectivity[std::size_t(k)];
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], float(p[a]));
      hi[a] = std::max(hi[a], float(p[a]));
    }
  }
}

}  // namespace

void prepare_mesh(Mesh& mesh, CellDataMode mode) {
  if (mesh.cell_values && mode == CellDataMode::points) {
    mesh.values = cell_values_to_points(mesh);
    mesh.cell_values = false;
  }
}

namespace {

double tet_volume(const double* p0, const double* p1, const double* p2, const double* p3) {
  double e[3][3];
  for (int a = 0; a < 3; ++a) {
    e[0][a] = p1[a] - p0[a];
    e[1][a] = p2[a] - p0[a];
    e[2][a] = p3[a] - p0[a];
  }
  const double det = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                     e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                     e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
  return std::fabs(det) / 6.0;
}

// Six tetrahedra around a hexahedron's diagonal 0–6 (VTK order): its volume for planar faces,
// close to it otherwise (a cell's size only decides where to split).
constexpr int kHexTets[6][4] = {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6},
                                {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}};

// Volume of each cell of m: hexahedra and voxels by kHexTets (most CFD meshes are hexahedra,
// and splitting them conformingly costs as much as reading the mesh), the other cells as the
// sum of the voxelizer's tetrahedra.
std::vector<double> cell_volumes(const Mesh& m) {
  std::vector<double> v(std::size_t(m.cell_count()), 0.0);
  for (std::int64_t c = 0; c < m.cell_count(); ++c) {
    const CellType type = m.types[std::size_t(c)];
    if (!is_hexahedral(type)) continue;
    const std::int64_t* q = m.connectivity.data() + m.offsets[std::size_t(c)];
    const double* p[8];
    for (int i = 0; i < 8; ++i)
      p[i] = m.points.data() + 3 * q[type == CellType::voxel ? kVoxelToHex[i] : i];
    for (const auto& t : kHexTets) v[std::size_t(c)] += tet_volume(p[t[0]], p[t[1]], p[t[2]], p[t[3]]);
  }
  const TetMesh tm = tetrahedralize(m, /*skip_hexahedra=*/true);
  for (std::size_t k = 0; k < tm.tets.size(); ++k) {
    const auto& t = tm.tets[k];
    const double* pts = tm.points.data();
    v[std::size_t(tm.cell[k])] += tet_volume(pts + 3 * t[0], pts + 3 * t[1], pts + 3 * t[2], pts + 3 * t[3]);
  }
  return v;
}

// Per cell of m: its box and its size (MeshScan::kSummary floats), into out; united with `with`
// (the same cells' earlier summary) when given, whose sizes are kept. A cell's size is its
// thinnest extent, volume / (largest box edge)²: a slab's thickness, a cube's edge, a sliver's
// height, so thin shells (the crushing can's) count as the fine detail they are.
// volumes: m's cell_volumes when the caller has them.
void summarise(const Mesh& m, std::vector<float>& out, const std::vector<float>* with,
               const std::vector<double>* volumes = nullptr) {
  const std::int64_t n = m.cell_count();
  out.resize(std::size_t(MeshScan::kSummary * n));
  const std::vector<double> own = with || volumes ? std::vector<double>{} : cell_volumes(m);
  const std::vector<double>& volume = volumes ? *volumes : own;
  for (std::int64_t c = 0; c < n; ++c) {
    float l[3], h[3];
    cell_box(m, c, l, h);
    float* box = out.data() + MeshScan::kSummary * c;
    const float* old = with ? with->data() + MeshScan::kSummary * c : nullptr;
    for (int a = 0; a < 3; ++a) {
      box[a] = old ? std::min(old[a], l[a]) : l[a];
      box[3 + a] = old ? std::max(old[3 + a], h[a]) : h[a];
    }
    const double edge = std::max({h[0] - l[0], h[1] - l[1], h[2] - l[2]});
    box[6] = old ? old[6] : edge > 0 ? float(volume[std::size_t(c)] / (edge * edge)) : 0.f;
  }
}

// Per cell of m: min and max of its finite values (min > max when none).
void value_ranges(const Mesh& m, std::vector<float>& out) {
  const std::int64_t n = m.cell_count();
  out.resize(std::size_t(2 * n));
  for (std::int64_t c = 0; c < n; ++c) {
    float lo = kInf, hi = -kInf;
    auto take = [&](float v) {
      if (!std::isfinite(v)) return;
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    };
    if (m.cell_values) {
      take(m.values[std::size_t(c)]);
    } else {
      for (std::int64_t k = m.offsets[std::size_t(c)]; k < m.offsets[std::size_t(c) + 1]; ++k)
        take(m.values[std::size_t(m.connectivity[std::size_t(k)])]);
    }
    out[std::size_t(2 * c)] = lo;
    out[std::size_t(2 * c + 1)] = hi;
  }
}

}  // namespace

MeshScan scan_mesh(MeshSource& source, CellDataMode mode, const std::string& dir) {
  MeshScan s;
  s.steps = source.steps();
  s.ranges = std::make_unique<DiskLists<float>>(dir, s.steps, "the cells' value ranges");
  s.summary = std::make_unique<DiskLists<float>>(dir, s.steps, "the cells' boxes");
  float lo = kInf, hi = -kInf;
  std::vector<float> summary, earlier, range;
  std::vector<std::int64_t> counts;
  auto read = [&](int t) {
    Mesh m = source.read_step(t);
    prepare_mesh(m, mode);
    return m;
  };
  for (int t = 0; t < s.steps; ++t) {
    Mesh m = read(t);
    struct Keep {  // the last step's mesh stays with the scan, however this step ends
      MeshScan& s;
      Mesh& m;
      bool last;
      ~Keep() {
        if (last) s.last = std::move(m);
      }
    } keep{s, m, t + 1 == s.steps};
    const std::int64_t n = m.cell_count();
    if (n == 0)
      throw FormatError(source.describe() + ": step " + std::to_string(t) + " has no cells");
    const std::vector<double> volumes = t == 0 ? cell_volumes(m) : std::vector<double>{};
    if (t == 0) s.median_cell = median_cell_size(volumes);
    counts.push_back(n);
    const Aabb b = m.bounds();
    for (int a = 0; a < 3; ++a) {
      s.bounds.lo[a] = t ? std::min(s.bounds.lo[a], b.lo[a]) : b.lo[a];
      s.bounds.hi[a] = t ? std::max(s.bounds.hi[a], b.hi[a]) : b.hi[a];
    }
    for (float v : m.values) {
      if (!std::isfinite(v)) {
        ++s.nonfinite;
        continue;
      }
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    value_ranges(m, range);
    s.ranges->put(t, range);
    if (s.shared && t > 0 && n == counts[0]) {  // the same cells: their boxes span both steps
      earlier = s.summary->get(0);
      summarise(m, summary, &earlier);
      s.summary->put(0, summary);
      continue;
    }
    if (s.shared && t > 0) {
      // A remeshed series: every step gets its own cells; the earlier steps are read again
      // for their own boxes (step 0's summary so far spans them all).
      s.shared = false;
      for (int k = 0; k < t; ++k) {
        summarise(read(k), summary, nullptr);
        s.summary->put(k, summary);
      }
    }
    summarise(m, summary, nullptr, t == 0 ? &volumes : nullptr);
    s.summary->put(t, summary);
  }
  s.cells = s.shared ? std::vector<std::int64_t>{counts[0]} : counts;
  s.data = lo <= hi ? ValueRange{lo, hi} : ValueRange{0, 0};
  return s;
}

Aabb node_region(const Octree& octree, const VoxelGrid& grid, int id) {
  const BrickLattice l = octree.lattice(octree.node_brick(id));
  Aabb r;
  for (int a = 0; a < 3; ++a) {
    const double margin = l.factor[a] + 1;
    r.lo[a] = grid.origin[a] + (l.origin[a] - margin) * grid.spacing[a];
    r.hi[a] = grid.origin[a] +
              (l.origin[a] + double(l.samples[a] - 1) * l.factor[a] + margin) * grid.spacing[a];
  }
  return r;
}

Subdivision subdivide(const Octree& octree, const VoxelGrid& grid, const MeshScan& scan,
                      double error, CellLists& lists) {
  Subdivision out;
  out.stopped.assign(std::size_t(octree.size()), 0);
  const int ls = scan.list_steps();
  auto key = [ls](int node, int s) { return std::int64_t(node) * ls + s; };
  for (int s = 0; s < ls; ++s) {
    std::vector<std::int64_t> all(std::size_t(scan.cells[std::size_t(s)]));
    std::iota(all.begin(), all.end(), std::int64_t(0));
    lists.put(key(0, s), all);
  }
  std::vector<std::uint8_t> has_list(std::size_t(octree.size()), 0);
  has_list[0] = 1;
  std::vector<float> summary;  // list step cached's cell summary
  int cached = -1;
  auto summary_of = [&](int s) -> const std::vector<float>& {
    if (s != cached) {
      summary = scan.summary->get(s);
      cached = s;
    }
    return summary;
  };
  // Nodes are numbered breadth-first: each level is a run of ids, its children the next run.
  for (int first = 0, last = 0; first < octree.size(); first = last) {
    const int level = octree.node(first).level;
    last = first;
    while (last < octree.size() && octree.node(last).level == level) ++last;
    // Candidates: internal nodes with cells some of which are smaller than the node's voxels.
    std::vector<char> fine(std::size_t(last - first), 0), any(fine);
    for (int s = 0; s < ls; ++s) {
      const std::vector<float>& summary = summary_of(s);
      for (int id = first; id < last; ++id) {
        if (!has_list[std::size_t(id)] || octree.node(id).is_leaf()) continue;
        const auto f = octree.lod_factor(id);
        double edge = 0;
        for (int a = 0; a < 3; ++a) edge = std::max(edge, f[a] * grid.spacing[a]);
        const std::vector<std::int64_t> cells = lists.get(key(id, s));
        any[std::size_t(id - first)] |= !cells.empty();
        fine[std::size_t(id - first)] |= std::any_of(cells.begin(), cells.end(), [&](std::int64_t c) {
          return summary[std::size_t(MeshScan::kSummary * c + 6)] < edge;
        });
      }
    }
    // Their field's largest spread over the steps, one step's value ranges in memory at a time.
    std::vector<float> spread(fine.size(), 0.f);
    for (int t = 0; t < scan.steps; ++t) {
      if (std::none_of(fine.begin(), fine.end(), [](char f) { return f != 0; })) break;
      const std::vector<float> range = scan.ranges->get(t);
      for (int id = first; id < last; ++id) {
        if (!fine[std::size_t(id - first)]) continue;
        float lo = kInf, hi = -kInf;
        for (std::int64_t c : lists.get(key(id, scan.list_step(t)))) {
          lo = std::min(lo, range[std::size_t(2 * c)]);
          hi = std::max(hi, range[std::size_t(2 * c + 1)]);
        }
        if (lo <= hi) spread[std::size_t(id - first)] = std::max(spread[std::size_t(id - first)], hi - lo);
      }
    }
    std::vector<int> split;
    for (int id = first; id < last; ++id) {
      if (!has_list[std::size_t(id)]) continue;
      ++out.reachable;
      if (octree.node(id).is_leaf()) continue;
      const std::size_t k = std::size_t(id - first);
      if (any[k] && fine[k] && double(spread[k]) > error) {
        split.push_back(id);
        for (int c : octree.node(id).children)
          if (c >= 0) has_list[std::size_t(c)] = 1;
      } else {
        out.stopped[std::size_t(id)] = 1;
        ++out.stopped_count;
      }
    }
    // The split nodes' cells go to their children, one list step's boxes in memory at a time.
    for (int s = 0; s < ls && !split.empty(); ++s) {
      const std::vector<float>& summary = summary_of(s);
      for (int id : split) {
        const std::vector<std::int64_t> cells = lists.get(key(id, s));
        for (int c : octree.node(id).children) {
          if (c < 0) continue;
          const Aabb r = node_region(octree, grid, c);
          std::vector<std::int64_t> mine;
          for (std::int64_t cell : cells) {
            const float* b = summary.data() + MeshScan::kSummary * cell;
            bool meets = true;
            for (int a = 0; a < 3; ++a) meets = meets && b[a] <= r.hi[a] && b[3 + a] >= r.lo[a];
            if (meets) mine.push_back(cell);
          }
          lists.put(key(c, s), mine);
        }
      }
    }
  }
  return out;
}

}  // namespace tsp
