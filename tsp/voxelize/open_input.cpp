#include "tsp/voxelize/open_input.h"

#include "tsp/source/open_mesh_source.h"
#include "tsp/source/open_source.h"

namespace tsp {

std::unique_ptr<VolumeSource> open_input(const std::string& input, const SourceOptions& options,
                                         const VoxelizeOptions& voxel) {
  if (is_mesh_input(input, options.allow_external))
    return voxelized_source(open_mesh_source(input, options.field, options.allow_external,
                                              options.plot3d_grid), voxel);
  return open_source(input, options);
}

}  // namespace tsp
