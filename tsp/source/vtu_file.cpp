#include "tsp/source/vtu_file.h"

#include <algorithm>

#include "tsp/core/error.h"

namespace tsp::io {
namespace {

using detail::components_of;
using detail::count_attribute;
using detail::piece_points;

pugi::xml_node required(const pugi::xml_node& section, const char* name, const std::string& where) {
  pugi::xml_node a = find_data_array(section, name);
  if (!a) throw FormatError(where + ": <" + section.name() + "> has no DataArray '" + name + "'");
  return a;
}

}  // namespace

VtuFile::VtuFile(const std::string& path) : XmlMeshFile(path, "UnstructuredGrid") {}

MeshField VtuFile::resolve(const FieldSpec& spec) const {
  return detail::resolve_field(doc_.dataset().child("Piece"), spec, path());
}

Aabb VtuFile::bounds() const {
  Aabb all;
  bool first = true;
  int index = 0;
  for (pugi::xml_node piece : doc_.dataset().children("Piece")) {
    const std::string pw = path() + ", piece " + std::to_string(index++);
    const std::int64_t np = count_attribute(piece, "NumberOfPoints", pw);
    Mesh m;
    const std::vector<float> xyz = piece_points(doc_, piece, np, pw);
    m.points.assign(xyz.begin(), xyz.end());
    if (m.points.empty()) continue;
    const Aabb b = m.bounds();
    for (int a = 0; a < 3; ++a) {
      all.lo[a] = first ? b.lo[a] : std::min(all.lo[a], b.lo[a]);
      all.hi[a] = first ? b.hi[a] : std::max(all.hi[a], b.hi[a]);
    }
    first = false;
  }
  return all;
}

Mesh VtuFile::read(const MeshField& f) const {
  Mesh m;
  m.cell_values = f.cells;
  m.offsets.push_back(0);
  bool any_faces = false;
  int index = 0;
  for (pugi::xml_node piece : doc_.dataset().children("Piece")) {
    const std::string pw = path() + ", piece " + std::to_string(index++);
    const std::int64_t np = count_attribute(piece, "NumberOfPoints", pw);
    const std::int64_t nc = count_attribute(piece, "NumberOfCells", pw);
    const std::int64_t base = m.point_count();
    const std::vector<float> xyz = piece_points(doc_, piece, np, pw);
    m.points.insert(m.points.end(), xyz.begin(), xyz.end());

    pugi::xml_node cells = piece.child("Cells");
    if (nc > 0 && !cells) throw FormatError(pw + ": " + std::to_string(nc) + " cells but no <Cells>");
    const std::vector<std::int64_t> ends =
        nc ? doc_.integers(required(cells, "offsets", pw), std::uint64_t(nc))
           : std::vector<std::int64_t>{};
    const std::vector<std::int64_t> types =
        nc ? doc_.integers(required(cells, "types", pw), std::uint64_t(nc))
           : std::vector<std::int64_t>{};
    // The connectivity's length is the last end offset; check the offsets before trusting it.
    std::int64_t prev = 0;
    for (std::int64_t c = 0; c < nc; ++c) {
      if (ends[std::size_t(c)] < prev)
        throw FormatError(pw + ", array offsets: entry " + std::to_string(c) + " is " +
                          std::to_string(ends[std::size_t(c)]) + ", below the previous " +
                          std::to_string(prev));
      prev = ends[std::size_t(c)];
    }
    const std::vector<std::int64_t> conn =
        nc ? doc_.integers(required(cells, "connectivity", pw), std::uint64_t(prev))
           : std::vector<std::int64_t>{};
    const std::int64_t conn_base = std::int64_t(m.connectivity.size());
    for (std::size_t k = 0; k < conn.size(); ++k) {
      if (conn[k] < 0 || conn[k] >= np)
        throw FormatError(pw + ", array connectivity: entry " + std::to_string(k) + " is point " +
                          std::to_string(conn[k]) + ", expected 0.." + std::to_string(np - 1));
      m.connectivity.push_back(conn[k] + base);
    }
    for (std::int64_t c = 0; c < nc; ++c) {
      m.offsets.push_back(conn_base + ends[std::size_t(c)]);
      const std::int64_t t = types[std::size_t(c)];
      if (!is_supported_cell_type(t))
        throw FormatError(pw + ": cell " + std::to_string(c) + " has type " + std::to_string(t) +
                          ", expected tetra (10), voxel (11), hexahedron (12), wedge (13), "
                          "pyramid (14) or polyhedron (42)");
      m.types.push_back(CellType(t));
    }
    // Polyhedra: "faces" holds the streams, "faceoffsets" each cell's end in it (−1: none).
    pugi::xml_node fo = nc ? find_data_array(cells, "faceoffsets") : pugi::xml_node();
    const std::int64_t face_base = std::int64_t(m.faces.size());
    if (fo) {
      const std::vector<std::int64_t> fends = doc_.integers(fo, std::uint64_t(nc));
      std::int64_t last = 0;
      for (std::int64_t e : fends) last = std::max(last, e);
      std::vector<std::int64_t> faces =
          doc_.integers(required(cells, "faces", pw), std::uint64_t(last));
      m.face_start.resize(std::size_t(m.cell_count() - nc), -1);
      std::int64_t start = 0;
      for (std::int64_t c = 0; c < nc; ++c) {
        const std::int64_t e = fends[std::size_t(c)];
        if (e < 0) {
          m.face_start.push_back(-1);
          continue;
        }
        if (e < start)
          throw FormatError(pw + ", array faceoffsets: entry " + std::to_string(c) + " is " +
                            std::to_string(e) + ", below the previous " + std::to_string(start));
        m.face_start.push_back(face_base + start);
        // The stream [start, e) names the piece's points: move them to the mesh's (the counts
        // stay; a stream that runs short is check_mesh's to report).
        if (base > 0)
          for (std::int64_t pos = start + 1; pos < e;) {
            const std::int64_t n = faces[std::size_t(pos++)];
            for (std::int64_t k = 0; k < n && pos < e; ++k) faces[std::size_t(pos++)] += base;
          }
        start = e;
      }
      m.faces.insert(m.faces.end(), faces.begin(), faces.end());
      any_faces = true;
    } else if (any_faces) {
      m.face_start.resize(std::size_t(m.cell_count()), -1);
    }

    const std::vector<float> v = detail::piece_values(doc_, piece, f, f.cells ? nc : np, pw);
    m.values.insert(m.values.end(), v.begin(), v.end());
  }
  if (any_faces) m.face_start.resize(std::size_t(m.cell_count()), -1);
  check_mesh(m, path());
  return m;
}

}  // namespace tsp::io
