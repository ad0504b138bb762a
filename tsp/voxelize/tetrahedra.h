// tsp/voxelize: unstructured grids to regular grids (spec §3–4 of paper 000: cells to
// tetrahedra, the tet–box test, per-voxel sampling, pad and stencil); may include core/ and
// source/. This file: splitting every cell into tetrahedra.
//
// Conforming splits: every quadrilateral face is cut along the diagonal through its vertex of
// smallest global index, so the two cells sharing a face always cut it the same way (Dompierre
// et al. 1999). A hexahedron becomes 5 tetrahedra when its six diagonals form one of the two
// 5-tet patterns (paper 000), else 6 around a main diagonal when they form one of those four
// patterns, else 12 from its centroid (two per face); a wedge 3; a pyramid 2; a polyhedron one
// tetrahedron per face triangle from its centroid (faces fanned from their smallest vertex).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "tsp/source/mesh_source.h"

namespace tsp {

/// A mesh of tetrahedra carrying the source mesh's field.
struct TetMesh {
  std::vector<double> points;                    ///< x, y, z: the mesh's points, then centroids
  std::vector<std::array<std::int64_t, 4>> tets; ///< point indices
  std::vector<std::int64_t> cell;                ///< per tet, the cell it came from
  std::vector<float> values;                     ///< per point (centroids: the mean of their
                                                 ///< cell's points), or per cell
  bool cell_values = false;                      ///< values are per cell
};

/// Splits every cell of mesh (validated by check_mesh) as described above; with skip_hexahedra,
/// hexahedra and voxels give no tetrahedra (the voxelizer samples them whole). Tetrahedra come
/// in cell order. Never throws (asserts on a mesh check_mesh would reject).
TetMesh tetrahedralize(const Mesh& mesh, bool skip_hexahedra = false);

/// True for the cell types sampled whole in isoparametric mode (hexahedron, voxel). Never throws.
inline bool is_hexahedral(CellType t) { return t == CellType::hexahedron || t == CellType::voxel; }

/// VTK voxel point order to hexahedron order (voxels are axis-aligned hexahedra numbered
/// x fastest).
inline constexpr int kVoxelToHex[8] = {0, 1, 3, 2, 4, 5, 7, 6};

/// Per point, the mean of the values of the cells using it (for cell data read as point data);
/// points no cell uses get 0. Never throws.
std::vector<float> cell_values_to_points(const Mesh& mesh);

}  // namespace tsp
