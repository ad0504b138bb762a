#include "tsp/source/vtk/vti_file.h"

#include <algorithm>
#include <cassert>
#include <cctype>
#include <charconv>
#include <climits>
#include <cstdint>
#include <cmath>
#include <fstream>
#include <sstream>

#include "tsp/core/error.h"

namespace tsp::io {

using vtkxml::parse_extent;

VtiFile::VtiFile(const std::string& path, bool header_only)
    : doc_(path, "ImageData", header_only), image_(doc_.dataset()) {
  parse_extent(image_.attribute("WholeExtent").value(), whole_, path, "WholeExtent");
  if (!image_.child("Piece")) throw FormatError(path + ": <ImageData> has no <Piece>");
}

std::array<double, 6> VtiFile::geometry(const VtiField& f) const {
  std::array<double, 6> g{0, 0, 0, 1, 1, 1};
  for (int which = 0; which < 2; ++which) {
    const char* name = which ? "Spacing" : "Origin";
    if (!image_.attribute(name)) continue;
    std::istringstream in(image_.attribute(name).value());
    for (int a = 0; a < 3; ++a) {
      double v = 0;
      if (!(in >> v) || !std::isfinite(v) || (which && !(v > 0)))
        throw FormatError(path() + ": " + name + " \"" + image_.attribute(name).value() +
                          "\" is not 3 finite numbers" + (which ? " > 0" : ""));
      g[std::size_t(3 * which + a)] = v;
    }
  }
  if (f.cells)
    for (int a = 0; a < 3; ++a) g[std::size_t(a)] += 0.5 * g[std::size_t(3 + a)];
  return g;
}

VtiField VtiFile::resolve(const std::string& requested) const {
  pugi::xml_node piece = image_.child("Piece");
  std::vector<std::string> points = data_array_names(piece.child("PointData"));
  std::vector<std::string> cells = data_array_names(piece.child("CellData"));
  const std::string listing = "PointData: " + join_names(points) + "; CellData: " + join_names(cells);
  VtiField f;
  if (requested.empty()) {
    std::string scalars = piece.child("PointData").attribute("Scalars").value();
    if (points.size() == 1) {
      f.name = points[0];
    } else if (points.empty() && cells.size() == 1) {
      f = {cells[0], true};
    } else if (!scalars.empty() && std::count(points.begin(), points.end(), scalars)) {
      f.name = scalars;
    } else {
      throw FormatError(path() + ": no field given and no single array to default to (" + listing +
                        "); name one with --field");
    }
  } else if (std::count(points.begin(), points.end(), requested)) {
    f.name = requested;
  } else if (std::count(cells.begin(), cells.end(), requested)) {
    f = {requested, true};
  } else {
    throw FormatError(path() + ": field '" + requested +
                      "' not found; available arrays: " + listing);
  }
  pugi::xml_node array = find_data_array(piece.child(f.cells ? "CellData" : "PointData"), f.name);
  int comps = array.attribute("NumberOfComponents").as_int(1);
  if (comps != 1)
    throw FormatError(path() + ": field " + f.name + " has " + std::to_string(comps) +
                      " components; a scalar field is expected");
  return f;
}

Dims VtiFile::dims(const VtiField& f) const {
  long long n[3];
  for (int a = 0; a < 3; ++a) {
    const long long len = whole_[2 * a + 1] - whole_[2 * a];  // both within 32 bits
    n[a] = f.cells ? std::max(len, 1LL) : len + 1;
  }
  check_grid(n[0], n[1], n[2], 1, path() + ", WholeExtent");
  return Dims{int(n[0]), int(n[1]), int(n[2])};
}

void VtiFile::read(const VtiField& f, std::span<float> out) const {
  const Dims d = dims(f);
  assert(std::int64_t(out.size()) == d.count());
  std::vector<unsigned char> covered(out.size(), 0);
  int index = 0;
  for (pugi::xml_node piece : image_.children("Piece")) {
    const std::string pwhere = path() + ", piece " + std::to_string(index++);
    long long e[6];
    parse_extent(piece.attribute("Extent").value(), e, pwhere, "Extent");
    std::int64_t lo[3], n[3];
    for (int a = 0; a < 3; ++a) {
      if (e[2 * a] < whole_[2 * a] || e[2 * a + 1] > whole_[2 * a + 1])
        throw FormatError(pwhere + ": Extent lies outside WholeExtent");
      const bool flat = whole_[2 * a + 1] == whole_[2 * a];
      lo[a] = e[2 * a] - whole_[2 * a];
      n[a] = f.cells ? (flat ? 1 : e[2 * a + 1] - e[2 * a]) : e[2 * a + 1] - e[2 * a] + 1;
    }
    pugi::xml_node array = find_data_array(piece.child(f.cells ? "CellData" : "PointData"), f.name);
    if (!array)
      throw FormatError(pwhere + ": has no " + (f.cells ? "CellData" : "PointData") + " array '" +
                        f.name + "'");
    int comps = array.attribute("NumberOfComponents").as_int(1);
    if (comps != 1)
      throw FormatError(pwhere + ": field " + f.name + " has " + std::to_string(comps) +
                        " components; a scalar field is expected");
    const std::vector<float> buf = doc_.floats(array, std::uint64_t(n[0] * n[1] * n[2]));
    for (std::int64_t z = 0; z < n[2]; ++z)
      for (std::int64_t y = 0; y < n[1]; ++y)
        for (std::int64_t x = 0; x < n[0]; ++x) {
          std::size_t dst = std::size_t(((lo[2] + z) * d.y + lo[1] + y) * d.x + lo[0] + x);
          out[dst] = buf[std::size_t((z * n[1] + y) * n[0] + x)];
          covered[dst] = 1;
        }
  }
  auto gap = std::find(covered.begin(), covered.end(), 0);
  if (gap != covered.end()) {
    std::size_t i = std::size_t(gap - covered.begin());
    throw FormatError(path() + ": the pieces do not cover WholeExtent (sample " +
                      std::to_string(i % d.x) + "," + std::to_string(i / d.x % d.y) + "," +
                      std::to_string(i / d.x / d.y) + " of field " + f.name + " is missing)");
  }
}

}  // namespace tsp::io
