// PLOT3D inputs: binary 3-D grid files (.xyz: one or several blocks, single or double
// precision, with or without IBLANK, with or without Fortran record markers, either byte order,
// all detected from the file's size) and their solution files (.q: density, momentum, stagnation
// energy per point), one .q per time step, read as a MeshSource of hexahedra.
#pragma once
#include <memory>
#include <string>

#include "tsp/source/mesh_source.h"

namespace tsp {

/// True when input names PLOT3D files by their suffix: .q (one, or a pattern of them) or a grid
/// (.xyz) alone. Never throws.
bool is_plot3d_input(const std::string& input);

/// The fields a PLOT3D solution gives, as read (Density, Momentum (3 components),
/// StagnationEnergy) and derived as VTK's PLOT3D reader does (Velocity = Momentum / Density,
/// Pressure = (γ − 1)(StagnationEnergy − ½ |Momentum|² / Density), γ = 1.4). Never throws.
const char* plot3d_fields();

/// Opens the .q file (or pattern of them, one per step) `input` on `grid` (empty: the only .xyz
/// file in the first .q's folder) with field spec (empty: Density). Step times are the .q
/// headers' times when they increase, else 0, 1, 2, … Every file is read through the input
/// gate and its layout checked against its size before anything is allocated. Throws UsageError
/// (a grid given as the input, no grid found), IoError or FormatError naming the file and what
/// was expected versus found (a size that fits no layout, block sizes that differ between the
/// grid and a solution, an unknown field).
std::unique_ptr<MeshSource> open_plot3d_source(const std::string& input, const std::string& grid,
                                               const FieldSpec& spec);

}  // namespace tsp
