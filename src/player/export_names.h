// The names of what the window saves (S's pictures, movies): the dataset as the user named it,
// without the extensions of the kinds of file play reads.
#pragma once
#include <string>

namespace tspplayer {

/// The dataset part of a saved file's name: input's file name without its folder and without
/// every known input extension at its end, in any letter case (.tsp, .h5 .hdf5 .hdf .he5 .nc
/// .nc4 .vtkhdf, .vti .vtu .vts .vtm .pvd, .series, .q .xyz .raw):
/// "damBreakWithObstacle.vtu.series" → "damBreakWithObstacle" (S once saved
/// damBreakWithObstacle.vtu_alpha.water_step_0000.png). "tspplay" when nothing is left.
/// Never throws but bad_alloc.
std::string dataset_name(const std::string& input);

}  // namespace tspplayer
