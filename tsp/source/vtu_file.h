// One parsed VTK XML UnstructuredGrid (.vtu) file: its arrays, its points' bounds, and one
// field read into a validated Mesh. Used by the .vtu / .pvd / .vtm / .vtm.series readers.
#pragma once
#include <string>

#include "tsp/source/mesh_source.h"
#include "tsp/source/vtk/vtk_document.h"

namespace tsp::io {

/// A field chosen in a .vtu file: its array, PointData or CellData, and its component count.
struct VtuField {
  FieldSpec spec;
  bool cells = false;
  int components = 1;
};

/// A parsed .vtu file (all pieces concatenated into one mesh).
class VtuFile {
 public:
  /// Reads and parses path. Throws IoError (missing/unreadable) or FormatError (not XML, not
  /// UnstructuredGrid, no Piece, bad NumberOfPoints/NumberOfCells, unsupported encoding).
  explicit VtuFile(const std::string& path);
  /// The file's path.
  const std::string& path() const { return doc_.path(); }
  /// Resolves a request (empty name: the only array, else PointData's Scalars array). Throws
  /// FormatError listing the arrays when it is missing or ambiguous or does not fit the array.
  VtuField resolve(const FieldSpec& spec) const;
  /// Bounds of every piece's points. Throws FormatError on bad Points data.
  Aabb bounds() const;
  /// The mesh with field f, validated by check_mesh. Throws FormatError naming the file and
  /// the array on missing, truncated or inconsistent arrays.
  Mesh read(const VtuField& f) const;

 private:
  VtkDocument doc_;
};

}  // namespace tsp::io
