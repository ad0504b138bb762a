#include "tsp/surface/boundary.h"

#include <algorithm>
#include <unordered_map>

namespace tsp {

namespace detail {

// VTK's local point order of each fixed cell type's faces (vtkTetra, vtkVoxel, vtkHexahedron,
// vtkWedge, vtkPyramid); −1 ends a triangle.
struct FaceTable {
  int count;
  int faces[6][4];
};

const FaceTable& face_table(CellType t) {
  static const FaceTable tetra{4, {{0, 1, 3, -1}, {1, 2, 3, -1}, {2, 0, 3, -1}, {0, 2, 1, -1}}};
  static const FaceTable voxel{
      6, {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}}};
  static const FaceTable hexahedron{
      6, {{0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 4}, {3, 7, 6, 2}, {0, 3, 2, 1}, {4, 5, 6, 7}}};
  static const FaceTable wedge{
      5, {{0, 1, 2, -1}, {3, 5, 4, -1}, {0, 3, 4, 1}, {1, 4, 5, 2}, {2, 5, 3, 0}}};
  static const FaceTable pyramid{
      5, {{0, 3, 2, 1}, {0, 1, 4, -1}, {1, 2, 4, -1}, {2, 3, 4, -1}, {3, 0, 4, -1}}};
  switch (t) {
    case CellType::tetra: return tetra;
    case CellType::voxel: return voxel;
    case CellType::hexahedron: return hexahedron;
    case CellType::wedge: return wedge;
    case CellType::pyramid: return pyramid;
    case CellType::polyhedron: break;
  }
  static const FaceTable none{0, {}};
  return none;
}

// One face of one cell: its point ids in the cell's order.
struct Face {
  std::int64_t cell;
  std::vector<std::int64_t> points;
};

// A face's key: its point ids sorted.
struct KeyHash {
  std::size_t operator()(const std::vector<std::int64_t>& k) const {
    std::size_t h = k.size();
    for (std::int64_t v : k) h ^= std::hash<std::int64_t>()(v) + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
    return h;
  }
};

std::array<double, 3> point(const Mesh& m, std::int64_t i) {
  return {m.points[std::size_t(3 * i)], m.points[std::size_t(3 * i + 1)],
          m.points[std::size_t(3 * i + 2)]};
}

}  // namespace detail

BoundaryTriangles boundary_triangles(const Mesh& mesh) {
  using detail::Face;
  std::vector<Face> faces;
  for (std::int64_t c = 0; c < mesh.cell_count(); ++c) {
    const std::int64_t* pts = mesh.connectivity.data() + mesh.offsets[std::size_t(c)];
    const CellType type = mesh.types[std::size_t(c)];
    if (type == CellType::polyhedron) {
      std::int64_t at = mesh.face_start[std::size_t(c)];
      const std::int64_t n = mesh.faces[std::size_t(at++)];
      for (std::int64_t f = 0; f < n; ++f) {
        const std::int64_t k = mesh.faces[std::size_t(at++)];
        Face face{c, {}};
        for (std::int64_t i = 0; i < k; ++i) face.points.push_back(mesh.faces[std::size_t(at++)]);
        faces.push_back(std::move(face));
      }
      continue;
    }
    const detail::FaceTable& table = detail::face_table(type);
    for (int f = 0; f < table.count; ++f) {
      Face face{c, {}};
      for (int i = 0; i < 4 && table.faces[f][i] >= 0; ++i) face.points.push_back(pts[table.faces[f][i]]);
      faces.push_back(std::move(face));
    }
  }
  // Count each face by its sorted point ids: a face two cells share is inside the mesh.
  std::unordered_map<std::vector<std::int64_t>, int, detail::KeyHash> count;
  count.reserve(faces.size());
  std::vector<std::vector<std::int64_t>> keys(faces.size());
  for (std::size_t i = 0; i < faces.size(); ++i) {
    keys[i] = faces[i].points;
    std::sort(keys[i].begin(), keys[i].end());
    ++count[keys[i]];
  }
  BoundaryTriangles out;
  for (std::size_t i = 0; i < faces.size(); ++i) {
    if (count[keys[i]] != 1) continue;
    const Face& f = faces[i];
    // The cell's centroid, to turn the face outwards.
    const std::int64_t b = mesh.offsets[std::size_t(f.cell)], e = mesh.offsets[std::size_t(f.cell) + 1];
    std::array<double, 3> centroid{0, 0, 0};
    for (std::int64_t k = b; k < e; ++k) {
      const auto p = detail::point(mesh, mesh.connectivity[std::size_t(k)]);
      for (int a = 0; a < 3; ++a) centroid[std::size_t(a)] += p[std::size_t(a)] / double(e - b);
    }
    for (std::size_t k = 1; k + 1 < f.points.size(); ++k) {
      std::array<std::int64_t, 3> t{f.points[0], f.points[k], f.points[k + 1]};
      const auto p0 = detail::point(mesh, t[0]), p1 = detail::point(mesh, t[1]),
                 p2 = detail::point(mesh, t[2]);
      std::array<double, 3> u{}, v{}, w{};
      for (int a = 0; a < 3; ++a) {
        u[std::size_t(a)] = p1[std::size_t(a)] - p0[std::size_t(a)];
        v[std::size_t(a)] = p2[std::size_t(a)] - p0[std::size_t(a)];
        w[std::size_t(a)] = p0[std::size_t(a)] - centroid[std::size_t(a)];
      }
      const double nx = u[1] * v[2] - u[2] * v[1], ny = u[2] * v[0] - u[0] * v[2],
                   nz = u[0] * v[1] - u[1] * v[0];
      if (nx * w[0] + ny * w[1] + nz * w[2] < 0) std::swap(t[1], t[2]);
      out.points.push_back(t);
      out.cell.push_back(f.cell);
    }
  }
  return out;
}

}  // namespace tsp
