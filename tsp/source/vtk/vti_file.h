// One parsed VTK XML ImageData (.vti) file: its grid, its arrays, and decoding of one scalar
// array into a whole-extent volume. Used by the .vti / .pvd / .vti.series readers.
#pragma once
#include <array>
#include <pugixml.hpp>
#include <span>
#include <string>
#include <vector>

#include "tsp/core/types.h"
#include "tsp/source/vtk/vtk_document.h"

namespace tsp::io {

/// A scalar array chosen in a .vti file: its name and whether it is CellData.
struct VtiField {
  std::string name;
  bool cells = false;
};

/// A parsed .vti file. Header-only documents skip the appended binary block (enough for the
/// grid and the array list, cheap for big files) and cannot read data.
class VtiFile {
 public:
  /// Reads and parses path. Throws IoError (missing/unreadable) or FormatError (not
  /// well-formed XML, not ImageData, bad WholeExtent, unsupported header type or compressor).
  VtiFile(const std::string& path, bool header_only);

  /// The file's path.
  const std::string& path() const { return doc_.path(); }

  /// Resolves the requested field (empty: the only array, else PointData's Scalars array).
  /// Throws FormatError listing the available arrays when it is missing or ambiguous, and
  /// when the array has more than one component.
  VtiField resolve(const std::string& requested) const;

  /// Grid size of a field: points of WholeExtent, or cells (a flat axis counts one cell).
  Dims dims(const VtiField& f) const;

  /// Origin and Spacing of <ImageData> (cell fields: of the cell centres); 0 and 1 when absent.
  /// Throws FormatError on values that are not 3 finite numbers or a spacing that is not > 0.
  std::array<double, 6> geometry(const VtiField& f) const;
  /// Decodes field f of every Piece into out (dims(f).count() floats, x fastest). Throws
  /// FormatError on missing arrays in a piece, truncated/corrupt data, pieces that leave
  /// part of WholeExtent uncovered.
  void read(const VtiField& f, std::span<float> out) const;

 private:
  VtkDocument doc_;
  pugi::xml_node image_;
  long long whole_[6] = {0, 0, 0, 0, 0, 0};
};

}  // namespace tsp::io
