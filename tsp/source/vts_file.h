// One parsed VTK XML StructuredGrid (.vts) file: a curvilinear grid, its points given one by
// one over an i, j, k extent, read as a Mesh of hexahedra (one per grid cell) that the
// voxelizer samples like any unstructured grid.
#pragma once
#include <string>

#include "tsp/source/mesh_file.h"

namespace tsp::io {

/// Appends the hexahedra of a structured block of n[0] × n[1] × n[2] points (i fastest), whose
/// first point is mesh point `base`, to mesh's offsets, connectivity and types (VTK's
/// hexahedron order: the k face counter-clockwise in i, j, then the k + 1 face). Never throws.
void append_structured_hexahedra(Mesh& mesh, const std::int64_t n[3], std::int64_t base);

/// A parsed .vts file (every piece's cells, each piece over its own Extent).
class VtsFile final : public XmlMeshFile {
 public:
  /// Reads and parses path. Throws IoError (missing/unreadable) or FormatError (not XML, not
  /// StructuredGrid, no Piece, a bad Extent, a 2-D or 1-D extent, which has no volume).
  explicit VtsFile(const std::string& path);
  MeshField resolve(const FieldSpec& spec) const override;
  Aabb bounds() const override;
  Mesh read(const MeshField& f) const override;
};

}  // namespace tsp::io
