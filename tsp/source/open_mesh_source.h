// Opening unstructured and curvilinear grid inputs: .vtu, .vts, .vtm, .pvd / .vtu.series /
// .vts.series / .vtm.series collections of them, patterns of .vtu or .vts files, VTKHDF
// UnstructuredGrid files (one, a pattern, or transient) and PLOT3D solutions (.q) on their grid.
#pragma once
#include <memory>
#include <string>

#include "tsp/source/mesh_source.h"

namespace tsp {

/// True when input names an unstructured grid this module reads (by name; for HDF5 files and
/// .pvd collections by looking inside). Never throws.
bool is_mesh_input(const std::string& input, bool allow_external = false);

/// Opens input (see is_mesh_input) with field "NAME[:mag|:x|:y|:z]" (empty: the only array).
/// Every step's header is checked at open. Throws UsageError (bad field suffix), IoError
/// (missing file) or FormatError naming the file, the array and what was expected versus found.
/// allow_external: HDF5 external links and storage are read (else refused, UsageError).
/// plot3d_grid: a PLOT3D solution's grid file (empty: the only .xyz beside the first .q).
std::unique_ptr<MeshSource> open_mesh_source(const std::string& input, const std::string& field,
                                             bool allow_external = false,
                                             const std::string& plot3d_grid = "");

}  // namespace tsp
