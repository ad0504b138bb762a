// Opening any input as a VolumeSource: regular grids through tsp::open_source, unstructured
// grids through their readers and the voxelizer.
#pragma once
#include <memory>
#include <string>

#include "tsp/source/volume_source.h"
#include "tsp/voxelize/voxelized_source.h"

namespace tsp {

/// An unstructured input (is_mesh_input) opened with options.field as "NAME[:mag|:x|:y|:z]" and
/// voxelized by voxel; anything else through open_source(input, options). Throws what those
/// throw.
std::unique_ptr<VolumeSource> open_input(const std::string& input, const SourceOptions& options,
                                         const VoxelizeOptions& voxel);

}  // namespace tsp
