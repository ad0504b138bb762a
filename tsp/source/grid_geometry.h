// Where a regular grid lies in space (origin and spacing per axis), from the Origin and Spacing
// an image-data file declares; shared by the .vti and VTKHDF image readers.
#pragma once
#include <array>
#include <optional>
#include <string>
#include <vector>

namespace tsp::io {

/// Voxel (i, j, k) lies at origin + (i, j, k)·spacing.
struct GridGeometry {
  std::array<double, 3> origin{0, 0, 0};
  std::array<double, 3> spacing{1, 1, 1};
};

/// The geometry of point data (cells: of the cell centres, half a spacing further) from declared
/// values (absent: 0 and 1). Throws FormatError naming `where` when a value is not finite, a
/// list is not 3 long, or a spacing is not positive.
GridGeometry image_geometry(const std::optional<std::vector<double>>& origin,
                            const std::optional<std::vector<double>>& spacing, bool cells,
                            const std::string& where);

}  // namespace tsp::io
