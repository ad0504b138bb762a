// Reader for VTKHDF UnstructuredGrid files (VTK's HDF5-based format): one file per step (a list
// or a pattern), or one transient file with a /VTKHDF/Steps group.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "tsp/source/mesh_source.h"

namespace tsp::io {

/// True when path is an HDF5 file whose /VTKHDF group holds an UnstructuredGrid (Type attribute,
/// or for version 1 files without one, a Connectivity dataset). Never throws.
bool is_vtkhdf_unstructured(const std::string& path);

/// Opens the VTKHDF UnstructuredGrid files, one step per file in order (one file: its Steps
/// group's NSteps steps, or one step). field selects a PointData array, else a CellData array;
/// an empty name picks the only array (or PointData's active Scalars). Polyhedra are not read
/// from VTKHDF (FormatError). Throws IoError or FormatError naming the file, the dataset and
/// what was expected versus found.
std::unique_ptr<MeshSource> open_vtkhdf_mesh_source(const std::string& input,
                                                    const std::vector<std::string>& files,
                                                    const FieldSpec& field);

}  // namespace tsp::io
