// One file of a structured or unstructured grid in VTK XML (.vtu UnstructuredGrid, .vts
// StructuredGrid): the interface the series readers use to resolve a field, read the points'
// bounds and read one validated Mesh, whichever kind the file is.
#pragma once
#include <memory>
#include <pugixml.hpp>
#include <string>

#include "tsp/source/mesh_source.h"
#include "tsp/source/vtk/vtk_document.h"

namespace tsp::io {

/// A field chosen in a mesh file: its array, PointData or CellData, and its component count.
struct MeshField {
  FieldSpec spec;
  bool cells = false;
  int components = 1;
};

/// A parsed mesh file (all pieces concatenated into one mesh).
class MeshFile {
 public:
  virtual ~MeshFile() = default;
  /// The file's path.
  virtual const std::string& path() const = 0;
  /// Resolves a request (empty name: the only array, else PointData's Scalars array). Throws
  /// FormatError listing the arrays when it is missing or ambiguous or does not fit the array.
  virtual MeshField resolve(const FieldSpec& spec) const = 0;
  /// Bounds of every piece's points. Throws FormatError on bad Points data.
  virtual Aabb bounds() const = 0;
  /// The mesh with field f, validated by check_mesh. Throws FormatError naming the file and
  /// the array on missing, truncated or inconsistent arrays.
  virtual Mesh read(const MeshField& f) const = 0;
};

/// A MeshFile parsed from one VTK XML document (.vtu, .vts): the document, its path.
class XmlMeshFile : public MeshFile {
 public:
  const std::string& path() const final { return doc_.path(); }

 protected:
  /// Reads and parses path as a VTK XML `type` with at least one Piece. Throws IoError
  /// (missing/unreadable) or FormatError (not XML, another type, no Piece).
  XmlMeshFile(const std::string& path, const char* type);
  VtkDocument doc_;
};

/// True when file's name is a mesh file this module reads (.vtu, .vts). Never throws.
bool is_mesh_file_name(const std::string& file);

/// Opens file as a .vtu or .vts by its name. Throws IoError / FormatError as the readers do.
std::unique_ptr<MeshFile> open_mesh_file(const std::string& file);

namespace detail {
/// A Piece's whole-number attribute (NumberOfPoints, …) ≥ 0. Throws FormatError naming where.
std::int64_t count_attribute(const pugi::xml_node& piece, const char* name,
                             const std::string& where);
/// An array's NumberOfComponents, 1..64. Throws FormatError naming where.
int components_of(const pugi::xml_node& array, const std::string& where);
/// A piece's points, np × 3 coordinates (zlib data inflating at most max_ratio:1). Throws
/// FormatError naming where.
std::vector<float> piece_points(const VtkDocument& doc, const pugi::xml_node& piece,
                                std::int64_t np, const std::string& where,
                                std::uint64_t max_ratio = vtkxml::kMaxInflateRatio);
/// Resolves spec against the first piece's PointData and CellData (see MeshFile::resolve).
MeshField resolve_field(const pugi::xml_node& piece, const FieldSpec& spec,
                        const std::string& path);
/// Reads piece's array of field f (tuples values, reduced to one value each). Throws
/// FormatError naming where when it is missing or its component count differs from f's.
std::vector<float> piece_values(const VtkDocument& doc, const pugi::xml_node& piece,
                                const MeshField& f, std::int64_t tuples, const std::string& where);
}  // namespace detail

}  // namespace tsp::io
