// What `tspplay play` (and the player's File > Open) plays: a .tsp file as it is, or any input
// `build` reads, built first into the cache folder's builds/ and reused while unchanged.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "tsp/adaptive/adaptive_build.h"
#include "tsp/build/build.h"
#include "tsp/source/volume_source.h"
#include "tsp/voxelize/voxelized_source.h"

namespace tspgl {

/// True when path is a .tsp file (an HDF5 file whose root has a `format` attribute), whatever
/// its name. Never throws.
bool is_tsp_file(const std::string& path);

/// True when name (a file name or path) ends like a kind of file play reads: .tsp, HDF5 / NetCDF-4
/// / VTKHDF (.h5 .hdf5 .hdf .he5 .nc .nc4 .vtkhdf), VTK (.vti .vtu .vtm .pvd and their .series)
/// or .raw, in any letter case. File > Open lists these unless "all files" is chosen (a file of
/// another name may still be read: HDF5 is recognised by its signature). Never throws.
bool has_input_extension(const std::string& name);

/// How an input that is not a .tsp file is read and built for playing: the same options as
/// `build` (src/cli/input_options.h).
struct PlayInputOptions {
  std::string field;              ///< the field to build, or A,B,C: several, the first shown
  tsp::SourceOptions source;      ///< how the input is read (its field is set per field)
  tsp::VoxelizeOptions voxelize;  ///< meshes: how they are voxelized
  std::string key;                ///< the options that change the build, as text (cache key)
  bool adaptive = false;          ///< meshes: Leven's adaptive octree (build --octree-error)
  tsp::AdaptiveOptions octree;    ///< its threshold (error, relative), when adaptive
};

/// Where input is built for playing with o: `DIR/builds/NAME-HASH.tsp` under cache_dir (""
/// : default_calibration_dir()), the hash over the input's absolute path, the field, o.key and
/// the absolute path, size and modification time (ns) of input and of every file in files (the
/// source's files(): series members, blocks, grid and solutions). Throws tsp::UsageError when
/// there is no cache folder.
std::string play_cache_path(const std::string& input, const PlayInputOptions& o,
                            const std::string& cache_dir, const std::vector<std::string>& files);

/// How a build for playing reports: `say` gets one line of text, `build` runs the build (a
/// progress bar, a cancel button) and returns its report.
struct PlayBuildHooks {
  std::function<void(const std::string&)> say;
  std::function<tsp::BuildReport(tsp::VolumeSource&, const std::string& out, tsp::BuildOptions)>
      build;
  /// Several fields into one file (as `build --field A,B,C`).
  std::function<void(const tsp::FieldSourceFn&, const std::vector<std::string>& fields,
                     const std::string& out, tsp::BuildOptions)>
      build_fields;
  /// Leven's adaptive octree of a mesh (as `build --octree-error`).
  std::function<void(tsp::MeshSource&, const std::string& out, tsp::AdaptiveOptions)> build_adaptive;
};

/// The .tsp file to play for input: input itself when it is a .tsp file (o.field then names one
/// of its fields, for the player), else play_cache_path's file, built with o (one field, or
/// several into one file) and build's defaults unless it exists. An entry that is not a regular
/// .tsp file of this user (a planted link, a FIFO, another user's file) is replaced, never
/// written through. Throws what opening or building the input throws, tsp::IoError when the entry
/// cannot be replaced.
std::string prepare_play_input(const std::string& input, const PlayInputOptions& o,
                               const std::string& cache_dir, const PlayBuildHooks& hooks);

}  // namespace tspgl
