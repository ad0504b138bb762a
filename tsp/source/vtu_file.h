// One parsed VTK XML UnstructuredGrid (.vtu) file: its arrays, its points' bounds, and one
// field read into a validated Mesh. Used by the .vtu / .pvd / .vtm / .vtm.series readers.
#pragma once
#include <string>

#include "tsp/source/mesh_file.h"

namespace tsp::io {

/// A parsed .vtu file (all pieces concatenated into one mesh).
class VtuFile final : public XmlMeshFile {
 public:
  /// Reads and parses path. Throws IoError (missing/unreadable) or FormatError (not XML, not
  /// UnstructuredGrid, no Piece, bad NumberOfPoints/NumberOfCells, unsupported encoding).
  explicit VtuFile(const std::string& path);
  MeshField resolve(const FieldSpec& spec) const override;
  Aabb bounds() const override;
  Mesh read(const MeshField& f) const override;
};

}  // namespace tsp::io
