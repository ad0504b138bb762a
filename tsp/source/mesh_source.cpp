#include "tsp/source/mesh_source.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tsp/core/error.h"

namespace tsp {

int cell_point_count(CellType t) {
  switch (t) {
    case CellType::tetra:
      return 4;
    case CellType::voxel:
    case CellType::hexahedron:
      return 8;
    case CellType::wedge:
      return 6;
    case CellType::pyramid:
      return 5;
    case CellType::polyhedron:
      return 0;
  }
  return 0;
}

bool is_supported_cell_type(std::int64_t code) {
  for (CellType t : {CellType::tetra, CellType::voxel, CellType::hexahedron, CellType::wedge,
                     CellType::pyramid, CellType::polyhedron})
    if (code == std::int64_t(t)) return true;
  return false;
}

Aabb Mesh::bounds() const {
  Aabb b;
  if (points.empty()) return b;
  for (int a = 0; a < 3; ++a) b.lo[a] = b.hi[a] = points[std::size_t(a)];
  for (std::size_t i = 0; i < points.size(); i += 3)
    for (int a = 0; a < 3; ++a) {
      b.lo[a] = std::min(b.lo[a], points[i + a]);
      b.hi[a] = std::max(b.hi[a], points[i + a]);
    }
  return b;
}

void check_mesh(const Mesh& m, const std::string& where) {
  const std::int64_t np = m.point_count(), nc = m.cell_count();
  if (m.points.size() % 3 != 0)
    throw FormatError(where + ": Points hold " + std::to_string(m.points.size()) +
                      " coordinates, not a multiple of 3");
  for (std::size_t i = 0; i < m.points.size(); ++i)
    if (!std::isfinite(m.points[i]))
      throw FormatError(where + ": point " + std::to_string(i / 3) + " has a non-finite coordinate");
  if (std::int64_t(m.offsets.size()) != nc + 1 || m.offsets.front() != 0 ||
      m.offsets.back() != std::int64_t(m.connectivity.size()))
    throw FormatError(where + ": cell offsets (" + std::to_string(m.offsets.size()) +
                      " entries, last " +
                      (m.offsets.empty() ? std::string("none") : std::to_string(m.offsets.back())) +
                      ") do not describe " + std::to_string(nc) + " cells over " +
                      std::to_string(m.connectivity.size()) + " connectivity entries");
  const std::int64_t expect = m.cell_values ? nc : np;
  if (std::int64_t(m.values.size()) != expect)
    throw FormatError(where + ": the field has " + std::to_string(m.values.size()) +
                      " values, expected " + std::to_string(expect) + " (one per " +
                      (m.cell_values ? "cell" : "point") + ")");
  if (!m.face_start.empty() && std::int64_t(m.face_start.size()) != nc)
    throw FormatError(where + ": face offsets have " + std::to_string(m.face_start.size()) +
                      " entries, expected one per cell (" + std::to_string(nc) + ")");
  for (std::int64_t c = 0; c < nc; ++c) {
    const std::int64_t b = m.offsets[std::size_t(c)], e = m.offsets[std::size_t(c) + 1];
    const std::string cw = where + ": cell " + std::to_string(c);
    if (e < b) throw FormatError(cw + ": offsets decrease (" + std::to_string(b) + " then " +
                                 std::to_string(e) + ")");
    const CellType t = m.types[std::size_t(c)];
    if (!is_supported_cell_type(std::int64_t(t)))
      throw FormatError(cw + ": cell type " + std::to_string(int(t)) +
                        " is not supported, expected tetra (10), voxel (11), hexahedron (12), "
                        "wedge (13), pyramid (14) or polyhedron (42)");
    const int need = cell_point_count(t);
    if (need > 0 && e - b != need)
      throw FormatError(cw + ": has " + std::to_string(e - b) + " points, its type " +
                        std::to_string(int(t)) + " needs " + std::to_string(need));
    if (t == CellType::polyhedron && e - b < 4)
      throw FormatError(cw + ": a polyhedron with " + std::to_string(e - b) + " points");
    for (std::int64_t k = b; k < e; ++k) {
      const std::int64_t p = m.connectivity[std::size_t(k)];
      if (p < 0 || p >= np)
        throw FormatError(cw + ": connectivity entry " + std::to_string(k) + " is point " +
                          std::to_string(p) + ", expected 0.." + std::to_string(np - 1));
    }
    if (t != CellType::polyhedron) continue;
    if (m.face_start.empty() || m.face_start[std::size_t(c)] < 0)
      throw FormatError(cw + ": a polyhedron without faces (no faces/faceoffsets arrays)");
    const std::int64_t nf_total = std::int64_t(m.faces.size());
    std::int64_t f = m.face_start[std::size_t(c)];
    auto at = [&](std::int64_t i) {
      if (i < 0 || i >= nf_total)
        throw FormatError(cw + ": its face stream runs past the faces array (" +
                          std::to_string(nf_total) + " entries)");
      return m.faces[std::size_t(i)];
    };
    const std::int64_t nfaces = at(f++);
    if (nfaces < 4 || nfaces > nf_total)
      throw FormatError(cw + ": face count " + std::to_string(nfaces) + ", expected 4 or more");
    const auto own_begin = m.connectivity.begin() + b, own_end = m.connectivity.begin() + e;
    for (std::int64_t i = 0; i < nfaces; ++i) {
      const std::int64_t n = at(f++);
      if (n < 3 || n > nf_total)
        throw FormatError(cw + ": face " + std::to_string(i) + " has " + std::to_string(n) +
                          " points, expected 3 or more");
      for (std::int64_t k = 0; k < n; ++k) {
        const std::int64_t p = at(f++);
        if (std::find(own_begin, own_end, p) == own_end)
          throw FormatError(cw + ": face " + std::to_string(i) + " names point " +
                            std::to_string(p) + ", which is not one of the cell's points");
      }
    }
  }
}

std::string FieldSpec::text() const {
  switch (pick) {
    case ComponentPick::magnitude: return name + ":mag";
    case ComponentPick::x: return name + ":x";
    case ComponentPick::y: return name + ":y";
    case ComponentPick::z: return name + ":z";
    case ComponentPick::scalar: break;
  }
  return name;
}

FieldSpec FieldSpec::parse(const std::string& spec) {
  FieldSpec f;
  const auto colon = spec.rfind(':');
  if (colon == std::string::npos) {
    f.name = spec;
    return f;
  }
  f.name = spec.substr(0, colon);
  const std::string c = spec.substr(colon + 1);
  if (c == "mag" || c == "magnitude") f.pick = ComponentPick::magnitude;
  else if (c == "x" || c == "0") f.pick = ComponentPick::x;
  else if (c == "y" || c == "1") f.pick = ComponentPick::y;
  else if (c == "z" || c == "2") f.pick = ComponentPick::z;
  else
    throw UsageError("--field " + spec + ": unknown component \"" + c +
                     "\", expected NAME, NAME:mag or NAME:x|y|z");
  return f;
}

std::vector<float> FieldSpec::reduce(const std::vector<float>& tuples, int components,
                                     const FieldSpec& spec, const std::string& where) {
  if (components < 1) throw FormatError(where + ": " + std::to_string(components) + " components");
  if (spec.pick == ComponentPick::scalar) {
    if (components != 1)
      throw FormatError(where + ": field " + spec.name + " has " + std::to_string(components) +
                        " components; name one with --field " + spec.name + ":mag or " +
                        spec.name + ":x|y|z");
    return tuples;
  }
  const std::size_t n = tuples.size() / std::size_t(components);
  std::vector<float> out(n);
  if (spec.pick == ComponentPick::magnitude) {
    for (std::size_t i = 0; i < n; ++i) {
      double s = 0;
      for (int k = 0; k < components; ++k) {
        const double v = tuples[i * std::size_t(components) + std::size_t(k)];
        s += v * v;
      }
      out[i] = float(std::sqrt(s));
    }
    return out;
  }
  const int k = spec.pick == ComponentPick::x ? 0 : spec.pick == ComponentPick::y ? 1 : 2;
  if (k >= components)
    throw FormatError(where + ": field " + spec.name + " has " + std::to_string(components) +
                      " components, component " + std::to_string(k) + " does not exist");
  for (std::size_t i = 0; i < n; ++i) out[i] = tuples[i * std::size_t(components) + std::size_t(k)];
  return out;
}

}  // namespace tsp
