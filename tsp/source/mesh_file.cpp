#include "tsp/source/mesh_file.h"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "tsp/core/error.h"
#include "tsp/source/series_list.h"
#include "tsp/source/vts_file.h"
#include "tsp/source/vtu_file.h"

namespace tsp::io {

XmlMeshFile::XmlMeshFile(const std::string& path, const char* type) : doc_(path, type, false) {
  if (!doc_.dataset().child("Piece"))
    throw FormatError(path + ": <" + type + "> has no <Piece>");
}

bool is_mesh_file_name(const std::string& file) {
  return has_suffix(file, ".vtu") || has_suffix(file, ".vts");
}

std::unique_ptr<MeshFile> open_mesh_file(const std::string& file) {
  if (has_suffix(file, ".vts")) return std::make_unique<VtsFile>(file);
  return std::make_unique<VtuFile>(file);
}

namespace detail {

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

std::vector<float> piece_points(const VtkDocument& doc, const pugi::xml_node& piece,
                                std::int64_t np, const std::string& where,
                                std::uint64_t max_ratio) {
  pugi::xml_node pts = piece.child("Points").child("DataArray");
  if (!pts) throw FormatError(where + ": no <Points> DataArray");
  if (components_of(pts, where + ", Points") != 3)
    throw FormatError(where + ": Points have " + pts.attribute("NumberOfComponents").value() +
                      " components, expected 3");
  std::vector<float> xyz = doc.floats(pts, std::uint64_t(np) * 3, max_ratio);
  // Here, not only in check_mesh: a later step's bounds are read without its cells, and an
  // infinite coordinate there became an infinite voxel size.
  for (std::size_t i = 0; i < xyz.size(); ++i)
    if (!std::isfinite(xyz[i]))
      throw FormatError(where + ": point " + std::to_string(i / 3) +
                        " has a non-finite coordinate (" + std::string(1, char('x' + i % 3)) +
                        " = " + std::to_string(xyz[i]) + ")");
  return xyz;
}

MeshField resolve_field(const pugi::xml_node& piece, const FieldSpec& spec,
                        const std::string& path) {
  std::vector<std::string> points = data_array_names(piece.child("PointData"));
  std::vector<std::string> cells = data_array_names(piece.child("CellData"));
  const std::string listing =
      "PointData: " + join_names(points) + "; CellData: " + join_names(cells);
  MeshField f;
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
      throw FormatError(path + ": no field given and no single array to default to (" +
                        listing + "); name one with --field");
    }
  } else if (std::count(points.begin(), points.end(), spec.name)) {
  } else if (std::count(cells.begin(), cells.end(), spec.name)) {
    f.cells = true;
  } else {
    throw FormatError(path + ": field '" + spec.name + "' not found; available arrays: " +
                      listing);
  }
  pugi::xml_node array =
      find_data_array(piece.child(f.cells ? "CellData" : "PointData"), f.spec.name);
  const std::string where = path + ", array " + f.spec.name;
  f.components = components_of(array, where);
  FieldSpec::reduce(std::vector<float>(std::size_t(f.components)), f.components, f.spec, where);
  return f;
}

std::vector<float> piece_values(const VtkDocument& doc, const pugi::xml_node& piece,
                                const MeshField& f, std::int64_t tuples, const std::string& where) {
  pugi::xml_node section = piece.child(f.cells ? "CellData" : "PointData");
  pugi::xml_node array = find_data_array(section, f.spec.name);
  if (!array)
    throw FormatError(where + ": has no " + (f.cells ? "CellData" : "PointData") + " array '" +
                      f.spec.name + "'");
  const std::string aw = where + ", array " + f.spec.name;
  const int comps = components_of(array, aw);
  if (comps != f.components)
    throw FormatError(aw + ": has " + std::to_string(comps) + " components, the first piece " +
                      std::to_string(f.components));
  return FieldSpec::reduce(doc.floats(array, std::uint64_t(tuples) * std::uint64_t(comps)), comps,
                           f.spec, aw);
}

}  // namespace detail
}  // namespace tsp::io
