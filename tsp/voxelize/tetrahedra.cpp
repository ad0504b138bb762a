#include "tsp/voxelize/tetrahedra.h"

#include <algorithm>
#include <cassert>

namespace tsp {
namespace {

using Tet = std::array<int, 4>;  // local vertex indices

// VTK hexahedron faces (each a cycle), and the two 5-tet and four 6-tet splits.
constexpr int kHexFaces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                 {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
constexpr Tet kFiveA[5] = {{0, 1, 2, 5}, {0, 2, 3, 7}, {0, 4, 5, 7}, {2, 5, 6, 7}, {0, 2, 5, 7}};
constexpr Tet kFiveB[5] = {{0, 1, 3, 4}, {1, 2, 3, 6}, {1, 4, 5, 6}, {3, 4, 6, 7}, {1, 3, 4, 6}};
// Main diagonal (a, b) and the ring of the other six vertices around it.
constexpr int kDiagonals[4][2] = {{0, 6}, {1, 7}, {2, 4}, {3, 5}};
constexpr int kRings[4][6] = {
    {1, 2, 3, 7, 4, 5}, {0, 3, 2, 6, 5, 4}, {1, 0, 3, 7, 6, 5}, {0, 1, 2, 6, 7, 4}};

struct Builder {
  const Mesh& mesh;
  TetMesh& out;

  void add(std::int64_t c, std::int64_t a, std::int64_t b, std::int64_t d, std::int64_t e) {
    out.tets.push_back({a, b, d, e});
    out.cell.push_back(c);
  }

  // A new point at the mean of pts (and, for point data, the mean of their values).
  std::int64_t centroid(const std::vector<std::int64_t>& pts) {
    // Sums of terms already divided by n: coordinates near the double range cannot overflow.
    double x[3] = {0, 0, 0}, v = 0;
    const double n = double(pts.size());
    for (std::int64_t p : pts) {
      for (int a = 0; a < 3; ++a) x[a] += mesh.points[std::size_t(3 * p + a)] / n;
      if (!out.cell_values) v += mesh.values[std::size_t(p)] / n;
    }
    for (int a = 0; a < 3; ++a) out.points.push_back(x[a]);
    if (!out.cell_values) out.values.push_back(float(v));
    return std::int64_t(out.points.size() / 3) - 1;
  }

  // Tetrahedra from point `apex` to each triangle of the polygon face (fanned from its smallest
  // global vertex, so the neighbour across the face cuts it the same way).
  void fan_face(std::int64_t c, std::int64_t apex, const std::vector<std::int64_t>& face) {
    const std::size_t n = face.size();
    const std::size_t m = std::size_t(std::min_element(face.begin(), face.end()) - face.begin());
    for (std::size_t k = 1; k + 1 < n; ++k)
      add(c, apex, face[m], face[(m + k) % n], face[(m + k + 1) % n]);
  }

  void hexahedron(std::int64_t c, const std::int64_t* g) {
    // Required diagonal of each face: through its smallest vertex.
    bool edge_needed[8][8] = {}, edge_banned[8][8] = {};
    for (const auto& f : kHexFaces) {
      int k = 0;
      for (int i = 1; i < 4; ++i)
        if (g[f[i]] < g[f[k]]) k = i;
      const int a = f[k], b = f[(k + 2) % 4], x = f[(k + 1) % 4], y = f[(k + 3) % 4];
      edge_needed[a][b] = edge_needed[b][a] = true;
      edge_banned[x][y] = edge_banned[y][x] = true;
    }
    auto fits = [&](const Tet* tets, int n) {
      bool has[8][8] = {};
      for (int t = 0; t < n; ++t)
        for (int i = 0; i < 4; ++i)
          for (int j = 0; j < 4; ++j) has[tets[t][i]][tets[t][j]] = true;
      for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 8; ++j)
          if ((edge_needed[i][j] && !has[i][j]) || (edge_banned[i][j] && has[i][j])) return false;
      return true;
    };
    for (const Tet* five : {kFiveA, kFiveB})
      if (fits(five, 5)) {
        for (int t = 0; t < 5; ++t) add(c, g[five[t][0]], g[five[t][1]], g[five[t][2]], g[five[t][3]]);
        return;
      }
    for (int d = 0; d < 4; ++d) {
      Tet six[6];
      for (int i = 0; i < 6; ++i)
        six[i] = {kDiagonals[d][0], kDiagonals[d][1], kRings[d][i], kRings[d][(i + 1) % 6]};
      if (fits(six, 6)) {
        for (const Tet& t : six) add(c, g[t[0]], g[t[1]], g[t[2]], g[t[3]]);
        return;
      }
    }
    const std::int64_t mid = centroid(std::vector<std::int64_t>(g, g + 8));
    for (const auto& f : kHexFaces) fan_face(c, mid, {g[f[0]], g[f[1]], g[f[2]], g[f[3]]});
  }

  void wedge(std::int64_t c, const std::int64_t* g) {
    // Relabel by the prism's symmetries so local 0 holds the smallest vertex.
    const int m = int(std::min_element(g, g + 6) - g);
    int p[6];
    for (int i = 0; i < 3; ++i) {
      const int bottom = (m % 3 + i) % 3;
      p[i] = m >= 3 ? bottom + 3 : bottom;
      p[i + 3] = m >= 3 ? bottom : bottom + 3;
    }
    auto v = [&](int i) { return g[p[i]]; };
    // Both quads at 0 are cut through 0; the third through its smaller diagonal end.
    if (std::min(v(1), v(5)) < std::min(v(2), v(4))) {
      add(c, v(0), v(1), v(2), v(5));
      add(c, v(0), v(1), v(5), v(4));
    } else {
      add(c, v(0), v(1), v(2), v(4));
      add(c, v(0), v(2), v(5), v(4));
    }
    add(c, v(0), v(4), v(5), v(3));
  }

  void pyramid(std::int64_t c, const std::int64_t* g) {
    const int m = int(std::min_element(g, g + 4) - g);
    if (m % 2 == 0) {
      add(c, g[0], g[1], g[2], g[4]);
      add(c, g[0], g[2], g[3], g[4]);
    } else {
      add(c, g[0], g[1], g[3], g[4]);
      add(c, g[1], g[2], g[3], g[4]);
    }
  }

  void polyhedron(std::int64_t c, const std::int64_t* g, std::int64_t n) {
    std::vector<std::int64_t> own(g, g + n);
    std::sort(own.begin(), own.end());
    own.erase(std::unique(own.begin(), own.end()), own.end());
    const std::int64_t mid = centroid(own);
    std::int64_t f = mesh.face_start[std::size_t(c)];
    const std::int64_t nfaces = mesh.faces[std::size_t(f++)];
    std::vector<std::int64_t> face;
    for (std::int64_t i = 0; i < nfaces; ++i) {
      const std::int64_t k = mesh.faces[std::size_t(f++)];
      face.assign(mesh.faces.begin() + f, mesh.faces.begin() + f + k);
      f += k;
      fan_face(c, mid, face);
    }
  }
};

}  // namespace

TetMesh tetrahedralize(const Mesh& mesh, bool skip_hexahedra) {
  TetMesh out;
  out.points = mesh.points;
  out.values = mesh.values;
  out.cell_values = mesh.cell_values;
  out.tets.reserve(std::size_t(mesh.cell_count()) * 5);
  out.cell.reserve(out.tets.capacity());
  Builder b{mesh, out};
  for (std::int64_t c = 0; c < mesh.cell_count(); ++c) {
    const std::int64_t* g = mesh.connectivity.data() + mesh.offsets[std::size_t(c)];
    const std::int64_t n = mesh.offsets[std::size_t(c) + 1] - mesh.offsets[std::size_t(c)];
    if (skip_hexahedra && is_hexahedral(mesh.types[std::size_t(c)])) continue;
    switch (mesh.types[std::size_t(c)]) {
      case CellType::tetra:
        b.add(c, g[0], g[1], g[2], g[3]);
        break;
      case CellType::voxel: {
        std::int64_t h[8];
        for (int i = 0; i < 8; ++i) h[i] = g[kVoxelToHex[i]];
        b.hexahedron(c, h);
        break;
      }
      case CellType::hexahedron:
        b.hexahedron(c, g);
        break;
      case CellType::wedge:
        b.wedge(c, g);
        break;
      case CellType::pyramid:
        b.pyramid(c, g);
        break;
      case CellType::polyhedron:
        b.polyhedron(c, g, n);
        break;
    }
  }
  return out;
}

std::vector<float> cell_values_to_points(const Mesh& mesh) {
  assert(mesh.cell_values);
  std::vector<double> sum(std::size_t(mesh.point_count()), 0.0);
  std::vector<std::int32_t> count(sum.size(), 0);
  for (std::int64_t c = 0; c < mesh.cell_count(); ++c) {
    std::int64_t b = mesh.offsets[std::size_t(c)], e = mesh.offsets[std::size_t(c) + 1];
    std::vector<std::int64_t> own(mesh.connectivity.begin() + b, mesh.connectivity.begin() + e);
    std::sort(own.begin(), own.end());
    own.erase(std::unique(own.begin(), own.end()), own.end());
    for (std::int64_t p : own) {
      sum[std::size_t(p)] += mesh.values[std::size_t(c)];
      ++count[std::size_t(p)];
    }
  }
  std::vector<float> out(sum.size(), 0.f);
  for (std::size_t p = 0; p < sum.size(); ++p)
    if (count[p]) out[p] = float(sum[p] / count[p]);
  return out;
}

}  // namespace tsp
