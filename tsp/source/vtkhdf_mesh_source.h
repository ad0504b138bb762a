// Reader for VTKHDF UnstructuredGrid files (VTK's HDF5-based format): one file per step (a list
// or a pattern), or one transient file with a /VTKHDF/Steps group.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "tsp/hdf5/hdf5_external.h"
#include "tsp/source/mesh_source.h"

namespace tsp::io {

/// True when path is an HDF5 file whose /VTKHDF group holds an UnstructuredGrid (Type attribute,
/// or for version 1 files without one, a Connectivity dataset), opened with external (refused
/// external links or storage: false). Never throws.
bool is_vtkhdf_unstructured(const std::string& path, h5::External external = h5::External::refuse);
/// The same test on a file already open. Never throws.
bool is_vtkhdf_unstructured(hid_t file);

/// Opens the VTKHDF UnstructuredGrid files, one step per file in order (one file: its Steps
/// group's NSteps steps, or one step). field selects a PointData array, else a CellData array;
/// an empty name picks the only array (or PointData's active Scalars). Polyhedra are not read
/// from VTKHDF (FormatError); nor are a Version other than 1.x or 2.x, or Steps/Values times
/// that are not finite and increasing. Every open checks what a file reads outside itself
/// (h5::check_external with external). Throws IoError, FormatError or UsageError (refused
/// external links or storage) naming the file, the dataset and what was expected versus found.
std::unique_ptr<MeshSource> open_vtkhdf_mesh_source(const std::string& input,
                                                    const std::vector<std::string>& files,
                                                    const FieldSpec& field,
                                                    h5::External external = h5::External::refuse);

}  // namespace tsp::io
