#include "tsp/frame/slicer.h"

#include <cassert>
#include <cmath>

#include "tsp/frame/slice_rules.h"

namespace tsp {
namespace {

using slice_rules::BoxFrame;

// Corner c has bit a set when it sits at hi on axis a. The box edge along axis a through corner
// c is numbered 4a + (the other two bits of c, lower axis first), so 0..11.
constexpr int edge_id(int c, int a) {
  const int b1 = a == 0 ? 1 : 0, b2 = a == 2 ? 1 : 2;
  return 4 * a + ((c >> b1) & 1) + 2 * ((c >> b2) & 1);
}

// Axes of corner c's three edges, counter-clockwise seen from outside the box. With s_a = ±1 the
// outward side of c on axis a, the edges run along −s_a·e_a and the order (x, y, z) is
// counter-clockwise from outside exactly when s_x·s_y·s_z > 0, i.e. when an odd number of c's
// bits are set.
constexpr std::array<int, 3> ccw_axes(int c) {
  const int bits = (c & 1) + ((c >> 1) & 1) + ((c >> 2) & 1);
  return bits % 2 == 1 ? std::array<int, 3>{0, 1, 2} : std::array<int, 3>{0, 2, 1};
}

// The active edge list: a circular doubly linked list over the 12 edge slots. `next` runs
// counter-clockwise seen from the deep side (the side already swept), so `prev` runs
// counter-clockwise seen from the eye. Each slot holds its edge's current intersection point.
struct ActiveEdges {
  std::array<int, 12> next{}, prev{};
  std::array<std::array<double, 3>, 12> point{};
  int head = -1;

  void link(int a, int b) {
    next[a] = b;
    prev[b] = a;
  }
};

// Sorts the corners by decreasing depth, equal depths by increasing tie key (insertion sort:
// 8 elements, mostly in order already).
std::array<int, 8> corner_order(const BoxFrame& f, const std::array<int, 8>& tie_key) {
  std::array<int, 8> order{0, 1, 2, 3, 4, 5, 6, 7};
  auto before = [&](int a, int b) {
    return f.depth[a] > f.depth[b] || (f.depth[a] == f.depth[b] && tie_key[a] < tie_key[b]);
  };
  for (int i = 1; i < 8; ++i) {
    const int c = order[i];
    int j = i;
    for (; j > 0 && before(c, order[j - 1]); --j) order[j] = order[j - 1];
    order[j] = c;
  }
  return order;
}

}  // namespace

IncrementalSlicer::IncrementalSlicer(const SlicePlanes& planes) : planes_(planes) {
  validate(planes_);
  for (int a = 0; a < 3; ++a) inv_dir_[a] = slice_rules::safe_inverse(planes_.dir[a]);
  // Sweeping back to front, each plane is `spacing` nearer; on an edge along axis a the point
  // with dot(p, dir) = depth moves by −spacing/dir[a]. Parallel edges share the slope.
  for (int e = 0; e < 12; ++e) slope_[e] = -planes_.spacing * inv_dir_[e / 4];
  // Corners at equal depth (computed) are ordered as if dir were tilted first towards the axis
  // most perpendicular to the view, then the next one (paper §4.2): the corner at the deep end
  // of that axis comes first. The deep end of an axis is hi when dir[a] ≥ 0. This key, like the
  // depth, never decreases from a corner to its neighbour at the near end of an axis, so the
  // sorted corners always respect the box's edges and the active edge list stays one cycle.
  std::array<int, 3> axes{0, 1, 2};
  for (int i = 1; i < 3; ++i)
    for (int j = i; j > 0 && std::abs(planes_.dir[axes[j]]) < std::abs(planes_.dir[axes[j - 1]]);
         --j)
      std::swap(axes[j], axes[j - 1]);
  for (int c = 0; c < 8; ++c) {
    tie_key_[c] = 0;
    for (int i = 0; i < 3; ++i) {
      const int a = axes[i];
      const int deep_bit = planes_.dir[a] >= 0 ? 1 : 0;
      if (((c >> a) & 1) != deep_bit) tie_key_[c] += 4 >> i;
    }
  }
}

void IncrementalSlicer::slice(const Aabb& box, PolygonSoup& out) const {
  BoxFrame f;
  if (!slice_rules::make_frame(planes_, box, f)) return;
  const std::array<int, 8> order = corner_order(f, tie_key_);
  const double near_corner = 2 * f.tol;

  ActiveEdges list;
  int processed = 0;  // bit c set once corner c has been passed
  auto init_edge = [&](int c, int a, double plane) {
    const int e = edge_id(c, a);
    auto& p = list.point[e];
    for (int b = 0; b < 3; ++b) p[b] = slice_rules::corner_coord(f, c, b);
    p[a] = slice_rules::edge_point(p[a], f.depth[c], plane, inv_dir_[a], f.lo[a], f.hi[a]);
    return e;
  };
  // Passes corner c: its edges whose other end was passed leave the list, the others enter it
  // at the place of the ones that leave (the spec's cases by number of unprocessed edges).
  auto pass_corner = [&](int c, double plane) {
    const std::array<int, 3> axes = ccw_axes(c);
    std::array<bool, 3> done{};
    int unprocessed = 0;
    for (int i = 0; i < 3; ++i) {
      done[i] = (processed >> (c ^ (1 << axes[i]))) & 1;
      unprocessed += done[i] ? 0 : 1;
    }
    processed |= 1 << c;
    switch (unprocessed) {
      case 3: {  // the first corner: its three edges in counter-clockwise order
        const int e0 = init_edge(c, axes[0], plane), e1 = init_edge(c, axes[1], plane),
                  e2 = init_edge(c, axes[2], plane);
        list.link(e0, e1);
        list.link(e1, e2);
        list.link(e2, e0);
        list.head = e0;
        break;
      }
      case 2: {  // replace the processed edge p by the two new ones, following p ccw at c
        int i = 0;
        while (!done[i]) ++i;
        const int p = edge_id(c, axes[i]);
        const int q = init_edge(c, axes[(i + 1) % 3], plane);
        const int r = init_edge(c, axes[(i + 2) % 3], plane);
        const int before = list.prev[p], after = list.next[p];
        list.link(before, q);
        list.link(q, r);
        list.link(r, after);
        list.head = q;
        break;
      }
      case 1: {  // replace the two processed edges (ccw at c: n, a, b; listed b, a) by n
        int i = 0;
        while (done[i]) ++i;
        const int a = edge_id(c, axes[(i + 1) % 3]), b = edge_id(c, axes[(i + 2) % 3]);
        assert(list.next[b] == a);
        const int n = init_edge(c, axes[i], plane);
        const int before = list.prev[b], after = list.next[a];
        list.link(before, n);
        list.link(n, after);
        list.head = n;
        break;
      }
      default:  // 0: the last corner; the list ends (never reached: no plane cuts below it)
        list.head = -1;
        break;
    }
  };

  const std::int64_t slices = f.k_first - f.k_last + 1;
  const std::size_t base = out.xyz.size();
  constexpr int kMaxVertices = 6;
  out.xyz.resize(base + std::size_t(slices) * kMaxVertices * 3);
  double* w = out.xyz.data() + base;
  int next_corner = 0;
  for (std::int64_t k = f.k_first; k >= f.k_last; --k) {
    const double plane = planes_.depth(k);
    // The bucket of this plane: corners between it and the previous plane (depth ≥ plane).
    while (next_corner < 8 && f.depth[order[next_corner]] >= plane)
      pass_corner(order[next_corner++], plane);
    // dmin < plane ≤ dmax, so at least the deepest corner is passed and the last one is not.
    assert(next_corner > 0 && next_corner < 8 && list.head >= 0);

    int n = 0;
    int e = list.head;
    do {
      const auto& p = list.point[e];
      w[3 * n] = p[0];
      w[3 * n + 1] = p[1];
      w[3 * n + 2] = p[2];
      ++n;
      e = list.prev[e];
    } while (e != list.head);
    assert(n >= 3 && n <= kMaxVertices);
    // Vertices can merge only when the plane passes within the tolerance of a corner; only then
    // is the polygon cleaned (the naive slicer always cleans, with the same rule).
    if (f.depth[order[next_corner - 1]] - plane <= near_corner ||
        plane - f.depth[order[next_corner]] <= near_corner)
      n = slice_rules::finish_polygon(w, n, planes_.dir, f.tol);
    if (n > 0) {
      out.counts.push_back(n);
      out.planes.push_back(k);
      w += 3 * n;
    }

    e = list.head;
    do {
      list.point[e][e / 4] += slope_[e];
      e = list.next[e];
    } while (e != list.head);
  }
  out.xyz.resize(std::size_t(w - out.xyz.data()));
}

}  // namespace tsp
