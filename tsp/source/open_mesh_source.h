// Opening unstructured-grid inputs: .vtu, .vtm, .pvd / .vtu.series / .vtm.series collections of
// them, patterns of .vtu files, and VTKHDF UnstructuredGrid files (one, a pattern, or transient).
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
std::unique_ptr<MeshSource> open_mesh_source(const std::string& input, const std::string& field,
                                             bool allow_external = false);

}  // namespace tsp
