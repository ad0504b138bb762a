// The heights of a WRF field's levels from the model's geopotential, (PH + PHB)/g per column
// and step: what places the levels at their heights (tsp/source/level_resample.h).
#pragma once
#include <hdf5.h>

#include <optional>
#include <string>

#include "tsp/core/types.h"
#include "tsp/source/level_resample.h"

namespace tsp::io {

/// Gravity WRF divides the geopotential by, m/s².
inline constexpr double kWrfGravity = 9.81;

/// The heights (metres) of every sample of a WRF field of `dims` over `steps` steps, read per
/// step from the file's geopotential PH + PHB (on the staggered levels, bottom_top_stag) divided
/// by kWrfGravity: a field on the staggered levels (W) takes them as they are, one on the mass
/// levels (T, QVAPOR, U, V; one level fewer) the midpoint of the two around it; a field one
/// wider than PH along x or y (U, V on the cell faces) the mean of the two columns beside it
/// (the nearest one at the edges). nullopt when the file has no PH and PHB of one 4-D shape
/// with `steps` steps whose levels and plane fit dims; the function it returns keeps its own
/// handle on the file, holds the HDF5 lock while it reads and throws FormatError naming
/// `where` when a read fails. Never throws.
std::optional<LevelHeightsFn> wrf_level_heights(hid_t file, Dims dims, int steps,
                                                const std::string& where);

}  // namespace tsp::io
