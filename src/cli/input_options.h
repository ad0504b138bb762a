// The options that say how to read an input (raw grid, mesh voxelization, HDF5 external data),
// registered once and shared by `build` and `play` (and so File > Open's builds): one owner per
// option, the same names, checks and help in both.
#pragma once
#include <string>

#include <CLI/CLI.hpp>

#include "tsp/adaptive/adaptive_build.h"
#include "tsp/source/volume_source.h"
#include "tsp/voxelize/voxelized_source.h"

namespace tspcli {

/// The input options as given on the command line.
struct InputArgs {
  std::string raw_dims, raw_type = "f32";
  bool big_endian = false;
  bool allow_external = false;
  int resolution = 0;
  double voxel_size = 0;
  std::string cell_data = "constant";
  std::string voxelizer = "locate", hex = "isoparametric";
  int antialias = 1;
  std::string jitter = "off";  ///< two-buffer: jittered sub-samples
  std::string xyz;  ///< PLOT3D grid of .q inputs
  std::string octree_error;  ///< meshes: E or P% of Leven's adaptive octree (empty: uniform)
  std::string vertical_levels = "finest";  ///< WRF: finest|native|N|Dm (tsp::VerticalLevels)
};

/// Adds --raw-dims, --raw-type, --big-endian, --allow-external, --resolution, --voxel-size,
/// --cell-data, --voxelizer, --antialias, --jitter, --hex, --xyz, --octree-error and
/// --vertical-levels to c, writing into a (which must outlive c).
void add_input_options(CLI::App* c, InputArgs& a);

/// The reader's options from a and field. Throws tsp::UsageError on a bad --raw-dims or
/// --vertical-levels.
tsp::SourceOptions source_options(const InputArgs& a, const std::string& field);

/// The voxelizer's options from a (threads: 0 for all cores). Throws tsp::UsageError when
/// --antialias is asked of the locating voxelizer.
tsp::VoxelizeOptions voxelize_options(const InputArgs& a, int threads);

/// Whether a asks for Leven's adaptive octree (--octree-error), and its threshold into o (error,
/// relative). Throws tsp::UsageError on a malformed or negative threshold.
bool octree_error(const InputArgs& a, tsp::AdaptiveOptions& o);

/// The options that change what a build of the input holds, as text (at the defaults only
/// --vertical-levels): part of the key of a build cached for playing.
std::string input_key(const InputArgs& a);

}  // namespace tspcli
