#include "tsp/source/vts_file.h"

#include <algorithm>

#include "tsp/core/error.h"

namespace tsp::io {
namespace {

// Most points one piece may declare (the file's arrays must then hold them, checked before any
// allocation); keeps the products of the extent's sizes far from overflow.
constexpr double kMaxPiecePoints = double(std::int64_t(1) << 40);
// Most a piece's zlib-compressed Points may inflate. Every point becomes a hexahedron of about
// 100 bytes in memory (its coordinates as doubles, 8 connectivity entries, an offset, a type,
// a value), so the deflate limit of 1032:1 let a 432 KB file declaring 300^3 points take 7.5 GB;
// real grids' coordinates compress 3-5:1 (a uniform grid stored as a .vts about 4.5:1).
constexpr std::uint64_t kMaxPointsInflateRatio = 64;

// A piece's points per axis from its Extent; refuses extents without volume. Throws
// FormatError naming where.
void piece_dims(const pugi::xml_node& piece, const std::string& where, std::int64_t n[3]) {
  long long e[6];
  vtkxml::parse_extent(piece.attribute("Extent").value(), e, where, "Extent");
  for (int a = 0; a < 3; ++a) n[a] = e[2 * a + 1] - e[2 * a] + 1;
  if (n[0] < 2 || n[1] < 2 || n[2] < 2)
    throw FormatError(where + ": Extent \"" + piece.attribute("Extent").value() + "\" is " +
                      std::to_string(n[0]) + " x " + std::to_string(n[1]) + " x " +
                      std::to_string(n[2]) +
                      " points: a surface or a line, expected at least 2 points on every axis "
                      "(a volume)");
  if (double(n[0]) * double(n[1]) * double(n[2]) > kMaxPiecePoints)
    throw FormatError(where + ": Extent \"" + piece.attribute("Extent").value() +
                      "\" declares more than 2^40 points");
}

}  // namespace

void append_structured_hexahedra(Mesh& mesh, const std::int64_t n[3], std::int64_t base) {
  const auto at = [&](std::int64_t i, std::int64_t j, std::int64_t k) {
    return base + i + n[0] * (j + n[1] * k);
  };
  if (mesh.offsets.empty()) mesh.offsets.push_back(0);
  for (std::int64_t k = 0; k + 1 < n[2]; ++k)
    for (std::int64_t j = 0; j + 1 < n[1]; ++j)
      for (std::int64_t i = 0; i + 1 < n[0]; ++i) {
        for (std::int64_t dk = 0; dk < 2; ++dk) {
          mesh.connectivity.push_back(at(i, j, k + dk));
          mesh.connectivity.push_back(at(i + 1, j, k + dk));
          mesh.connectivity.push_back(at(i + 1, j + 1, k + dk));
          mesh.connectivity.push_back(at(i, j + 1, k + dk));
        }
        mesh.offsets.push_back(std::int64_t(mesh.connectivity.size()));
        mesh.types.push_back(CellType::hexahedron);
      }
}

VtsFile::VtsFile(const std::string& path) : XmlMeshFile(path, "StructuredGrid") {
  int index = 0;
  for (pugi::xml_node piece : doc_.dataset().children("Piece")) {
    std::int64_t n[3];
    piece_dims(piece, path + ", piece " + std::to_string(index++), n);
  }
}

MeshField VtsFile::resolve(const FieldSpec& spec) const {
  return detail::resolve_field(doc_.dataset().child("Piece"), spec, path());
}

Aabb VtsFile::bounds() const {
  Mesh all;
  int index = 0;
  for (pugi::xml_node piece : doc_.dataset().children("Piece")) {
    const std::string pw = path() + ", piece " + std::to_string(index++);
    std::int64_t n[3];
    piece_dims(piece, pw, n);
    const std::vector<float> xyz =
        detail::piece_points(doc_, piece, n[0] * n[1] * n[2], pw, kMaxPointsInflateRatio);
    all.points.insert(all.points.end(), xyz.begin(), xyz.end());
  }
  return all.bounds();
}

Mesh VtsFile::read(const MeshField& f) const {
  Mesh m;
  m.cell_values = f.cells;
  m.offsets.push_back(0);
  int index = 0;
  for (pugi::xml_node piece : doc_.dataset().children("Piece")) {
    const std::string pw = path() + ", piece " + std::to_string(index++);
    std::int64_t n[3];
    piece_dims(piece, pw, n);
    const std::int64_t np = n[0] * n[1] * n[2];
    const std::int64_t nc = (n[0] - 1) * (n[1] - 1) * (n[2] - 1);
    const std::int64_t base = m.point_count();
    // Points first: the array's size check bounds what the cells below allocate.
    const std::vector<float> xyz =
        detail::piece_points(doc_, piece, np, pw, kMaxPointsInflateRatio);
    const std::vector<float> v = detail::piece_values(doc_, piece, f, f.cells ? nc : np, pw);
    m.points.insert(m.points.end(), xyz.begin(), xyz.end());
    append_structured_hexahedra(m, n, base);
    m.values.insert(m.values.end(), v.begin(), v.end());
  }
  check_mesh(m, path());
  return m;
}

}  // namespace tsp::io
