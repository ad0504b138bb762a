#include "tsp/source/vtu_file.h"

#include <algorithm>
#include <charconv>

#include "tsp/core/error.h"

namespace tsp::io {
namespace {

// A Piece's NumberOfPoints / NumberOfCells: a whole number ≥ 0. Throws FormatError.
std::int64_t count_attribute(const pugi::xml_node& piece, const char* name,
                             const std::string& where) {
  const std::string text = piece.attribute(name).value();
  std::int64_t v = -1;
  auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || ec != std::errc() || p != text.data() + text.size() || v < 0)
    throw FormatError(where + ": " + name + " \"" + text + "\" is not a whole number >= 0");
  return v;
}

int components_of(const pugi::xml_node& array, const std::string& where) {
  const int c = array.attribute("NumberOfComponents").as_int(1);
  if (c < 1 || c > 64)
    throw FormatError(where + ": NumberOfComponents " + std::to_string(c) + ", expected 1..64");
  return c;
}

pugi::xml_node required(const pugi::xml_node& section, const char* name, const std::string& where) {
  pugi::xml_node a = find_data_array(section, name);
  if (!a) throw FormatError(where + ": <" + section.name() + "> has no DataArray '" + name + "'");
  return a;
}

// A piece's points, NumberOfPoints × 3 coordinates. Throws FormatError naming `where`.
std::vector<float> piece_points(const VtkDocument& doc, const pugi::xml_node& piece,
                                std::int64_t np, const std::string& where) {
  pugi::xml_node pts = piece.child("Points").child("DataArray");
  if (!pts) throw FormatError(where + ": no <Points> DataArray");
  if (components_of(pts, where + ", Points") != 3)
    throw FormatError(where + ": Points have " + pts.attribute("NumberOfComponents").value() +
                      " components, expected 3");
  return doc.floats(pts, std::uint64_t(np) * 3);
}

}  // namespace

VtuFile::VtuFile(const std::string& path) : doc_(path, "UnstructuredGrid", false) {
  if (!doc_.dataset().child("Piece")) throw FormatError(path + ": <UnstructuredGrid> has no <Piece>");
}

VtuField VtuFile::resolve(const FieldSpec& spec) const {
  pugi::xml_node piece = doc_.dataset().child("Piece");
  std::vector<std::string> points = data_array_names(piece.child("PointData"));
  std::vector<std::string> cells = data_array_names(piece.child("CellData"));
  const std::string listing =
      "PointData: " + join_names(points) + "; CellData: " + join_names(cells);
  VtuField f;
  f.spec = spec;
  if (spec.name.empty()) {
    std::string scalars = piece.child("PointData").attribute("Scalars").value();
    if (points.size() == 1) {
      f.spec.name = points[0];
    } else if (points.empty() && cells.size() == 1) {
      f.spec.name = cells[0];
      f.cells = true;
    } else if (!scalars.empty() && std::count(points.begin(), points.end(), scalars)) {
      f.spec.name = scalars;
    } else {
      throw FormatError(path() + ": no field given and no single array to default to (" +
                        listing + "); name one with --field");
    }
  } else if (std::count(points.begin(), points.end(), spec.name)) {
  } else if (std::count(cells.begin(), cells.end(), spec.name)) {
    f.cells = true;
  } else {
    throw FormatError(path() + ": field '" + spec.name + "' not found; available arrays: " +
                      listing);
  }
  pugi::xml_node array =
      find_data_array(piece.child(f.cells ? "CellData" : "PointData"), f.spec.name);
  const std::string where = path() + ", array " + f.spec.name;
  f.components = components_of(array, where);
  FieldSpec::reduce(std::vector<float>(std::size_t(f.components)), f.components, f.spec, where);
  return f;
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

Mesh VtuFile::read(const VtuField& f) const {
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

    pugi::xml_node section = piece.child(f.cells ? "CellData" : "PointData");
    pugi::xml_node array = find_data_array(section, f.spec.name);
    if (!array)
      throw FormatError(pw + ": has no " + (f.cells ? "CellData" : "PointData") + " array '" +
                        f.spec.name + "'");
    const std::string aw = pw + ", array " + f.spec.name;
    const int comps = components_of(array, aw);
    if (comps != f.components)
      throw FormatError(aw + ": has " + std::to_string(comps) + " components, the first piece " +
                        std::to_string(f.components));
    const std::int64_t tuples = f.cells ? nc : np;
    const std::vector<float> v = FieldSpec::reduce(
        doc_.floats(array, std::uint64_t(tuples) * std::uint64_t(comps)), comps, f.spec, aw);
    m.values.insert(m.values.end(), v.begin(), v.end());
  }
  if (any_faces) m.face_start.resize(std::size_t(m.cell_count()), -1);
  check_mesh(m, path());
  return m;
}

}  // namespace tsp::io
