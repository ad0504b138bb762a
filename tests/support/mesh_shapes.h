// Unstructured meshes of known shape for tests: an n³ box of unit hexahedra.
#pragma once
#include "tsp/source/mesh_source.h"

namespace tsptest {

/// An n³ box of unit hexahedra ([0, n]³, VTK's corner order) whose point ids are shuffled by
/// seed (so every diagonal pattern and face order occurs); the point field is x. Passes
/// tsp::check_mesh.
tsp::Mesh hex_box(int n, unsigned seed);

}  // namespace tsptest
