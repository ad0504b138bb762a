// One parsed VTK XML ImageData (.vti) file: its grid, its arrays, and decoding of one scalar
// array into a whole-extent volume. Used by the .vti / .pvd / .vti.series readers.
#pragma once
#include <memory>
#include <pugixml.hpp>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "tsp/core/types.h"
#include "tsp/source/vtk/vtk_xml.h"

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
  const std::string& path() const { return path_; }

  /// Resolves the requested field (empty: the only array, else PointData's Scalars array).
  /// Throws FormatError listing the available arrays when it is missing or ambiguous, and
  /// when the array has more than one component.
  VtiField resolve(const std::string& requested) const;

  /// Grid size of a field: points of WholeExtent, or cells (a flat axis counts one cell).
  Dims dims(const VtiField& f) const;

  /// Decodes field f of every Piece into out (dims(f).count() floats, x fastest). Throws
  /// FormatError on missing arrays in a piece, truncated/corrupt data, pieces that leave
  /// part of WholeExtent uncovered.
  void read(const VtiField& f, std::span<float> out) const;

 private:
  void decode(const pugi::xml_node& array, std::span<float> out) const;

  std::string path_;
  std::string content_;  // file bytes (up to the appended block when header-only)
  std::unique_ptr<pugi::xml_document> doc_;
  pugi::xml_node image_;
  vtkxml::BinaryLayout layout_;
  long long whole_[6] = {0, 0, 0, 0, 0, 0};
  bool header_only_ = false;
  std::size_t appended_ = std::string::npos;      // first appended byte in content_
  std::size_t appended_end_ = std::string::npos;  // end of the appended block
  bool appended_base64_ = false;
  std::set<unsigned long long> appended_offsets_;  // every array's offset, to bound base64 runs
};

}  // namespace tsp::io
