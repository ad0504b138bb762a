// tsp/source: the interface unstructured-grid readers feed (VTK XML .vtu and its collections,
// VTKHDF UnstructuredGrid): one mesh with one scalar per point or per cell, per time step. The
// voxelizer (tsp/voxelize) turns it into a VolumeSource.
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "tsp/core/geometry.h"
#include "tsp/source/volume_source.h"

namespace tsp {

/// VTK cell type codes the voxelizer accepts (VTK's vtkCellType values).
enum class CellType : std::uint8_t {
  tetra = 10,
  voxel = 11,
  hexahedron = 12,
  wedge = 13,
  pyramid = 14,
  polyhedron = 42,
};

/// Number of points of a fixed-size cell type; 0 for polyhedra. Never throws.
int cell_point_count(CellType t);
/// True when code is one of CellType's values. Never throws.
bool is_supported_cell_type(std::int64_t code);

/// One step of an unstructured grid, validated by its reader: every connectivity index names a
/// point, every cell has its type's point count, every polyhedron a well-formed face stream.
struct Mesh {
  std::vector<double> points;             ///< x, y, z per point
  std::vector<std::int64_t> offsets;      ///< cells + 1 entries: cell c's points are
                                          ///< connectivity[offsets[c] .. offsets[c+1])
  std::vector<std::int64_t> connectivity; ///< point indices
  std::vector<CellType> types;            ///< per cell
  /// Polyhedra: cell c's faces start at faces[face_start[c]] (−1 for other cells) as VTK's
  /// face stream: face count, then per face its point count and point indices.
  std::vector<std::int64_t> face_start;
  std::vector<std::int64_t> faces;        ///< the face streams
  std::vector<float> values;              ///< the field: one per point, or one per cell
  bool cell_values = false;               ///< values are per cell (CellData)

  /// Number of points.
  std::int64_t point_count() const { return std::int64_t(points.size() / 3); }
  /// Number of cells.
  std::int64_t cell_count() const { return std::int64_t(types.size()); }
  /// Bounding box of the points (empty box when there are none). Never throws.
  Aabb bounds() const;
};

/// Validates a reader's mesh: sizes agree (offsets ascending from 0 to the connectivity size,
/// values per point or cell), every index names a point, every point is finite, every cell type
/// is supported with its point count, every polyhedron's face stream lies inside `faces` and
/// names the cell's own points. Throws FormatError naming `where` and the first offending cell.
void check_mesh(const Mesh& mesh, const std::string& where);

/// How to read a vector field: its magnitude or one component.
enum class ComponentPick { scalar, magnitude, x, y, z };

/// A field request "NAME", "NAME:mag" or "NAME:x|y|z|0|1|2", parsed.
struct FieldSpec {
  std::string name;                           ///< the array name (empty: the reader's default)
  ComponentPick pick = ComponentPick::scalar; ///< what to take of each tuple
  /// Parses spec; throws UsageError on an unknown suffix.
  static FieldSpec parse(const std::string& spec);
  /// The tuple reduced to one value (components = number of components per tuple). Throws
  /// FormatError naming where when the request does not fit the array (a component out of
  /// range, a scalar request on a vector array).
  static std::vector<float> reduce(const std::vector<float>& tuples, int components,
                                   const FieldSpec& spec, const std::string& where);
  /// The request as parse() reads it: "NAME", "NAME:mag", "NAME:x" … Never throws.
  std::string text() const;
};

/// A time series of unstructured grids carrying one field.
class MeshSource {
 public:
  virtual ~MeshSource() = default;
  /// Number of time steps T ≥ 1.
  virtual int steps() const = 0;
  /// Names what is read ("case.vtm.series, PointData T (40 steps)"), for messages and provenance.
  virtual std::string describe() const = 0;
  /// Every file it reads, so an output is never written over an input. Never throws.
  virtual std::vector<std::string> files() const = 0;
  /// Physical times of the steps when the input names them (.pvd, .series, VTKHDF
  /// Steps/Values), in step order; empty when it does not. Never throws.
  virtual std::vector<double> times() const = 0;
  /// Reads step t (0 ≤ t < steps()). Throws IoError or FormatError naming the file and array.
  virtual Mesh read_step(int t) = 0;
  /// Bounding box of step t's points (a reader may decode only the points). Throws like
  /// read_step.
  virtual Aabb bounds(int t) { return read_step(t).bounds(); }
  /// The field it reads (the one picked when none was named), as VolumeSource::field(). Never
  /// throws.
  virtual std::string field() const { return {}; }
};

}  // namespace tsp
