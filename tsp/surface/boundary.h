// tsp/surface: the surfaces of an unstructured mesh drawn as splats (TetSplat, seed paper 001
// §2–3): the mesh's boundary — its Shell, the cell faces no other cell shares — and the splat
// hierarchy over it (splat_tree.h) whose cut by a minimum splat size the renderer draws.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "tsp/source/mesh_source.h"

namespace tsp {

/// The boundary of a mesh as triangles: every face of a cell that no other cell shares (faces
/// matched by their point ids, whatever their order), fan-triangulated and turned so its normal
/// points away from its cell's centroid (outwards).
struct BoundaryTriangles {
  std::vector<std::array<std::int64_t, 3>> points;  ///< point ids per triangle
  std::vector<std::int64_t> cell;                   ///< the cell each triangle bounds
};

/// The mesh's boundary faces (tetrahedra, voxels, hexahedra, wedges, pyramids, polyhedra from
/// their face streams). The mesh must have passed check_mesh. Never throws (but bad_alloc).
BoundaryTriangles boundary_triangles(const Mesh& mesh);

}  // namespace tsp
