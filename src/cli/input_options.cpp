#include "cli/input_options.h"

#include <cmath>

#include "cli/args.h"
#include "tsp/core/error.h"
#include "tsp/source/level_resample.h"
#include "tsp/voxelize/voxelizer.h"

namespace tspcli {

namespace {
constexpr int kMaxRawEdge = 1 << 20;
}  // namespace

void add_input_options(CLI::App* c, InputArgs& a) {
  c->add_option("--resolution", a.resolution,
                "Meshes: samples on the longest edge (default: from the median cell size, 16..256)");
  c->add_option("--voxel-size", a.voxel_size, "Meshes: voxel edge in the mesh's units");
  c->add_option("--cell-data", a.cell_data,
                "Meshes, cell data: constant per cell, or averaged to the points then interpolated")
      ->check(CLI::IsMember({"constant", "points"}));
  c->add_option("--voxelizer", a.voxelizer,
                "Meshes: locate (voxel centres located in cells; default), scan (tetrahedra "
                "scan-converted plane by plane) or two-buffer (front and back faces into two "
                "buffers, the voxels between them stepped; paper 003), the last two with "
                "--antialias")
      ->check(CLI::IsMember({"locate", "scan", "two-buffer"}));
  c->add_option("--antialias", a.antialias,
                "Meshes, --voxelizer scan|two-buffer: K x K x K sub-samples per voxel, 1..4 "
                "(scan) or 1..5 (two-buffer) (default 1)")
      ->check(CLI::Range(1, tsp::kMaxTwoBufferK));
  c->add_option("--jitter", a.jitter,
                "Meshes, --voxelizer two-buffer: on moves each sub-sample by a fixed "
                "pseudo-random amount inside its sub-cell (default off)")
      ->check(CLI::IsMember({"on", "off"}));
  c->add_option("--hex", a.hex,
                "Meshes, locate: hexahedra sampled whole by their trilinear map (isoparametric, "
                "as VTK) or through tetrahedra")
      ->check(CLI::IsMember({"isoparametric", "tetrahedra"}));
  c->add_option("--xyz", a.xyz,
                 "PLOT3D input (.q solutions): their grid file (default: the only .xyz beside "
                 "the first .q)");
  c->add_option("--raw-dims", a.raw_dims, "Raw input: grid size X,Y,Z");
  c->add_option("--raw-type", a.raw_type, "Raw input: element type u8|u16|f32")
      ->check(CLI::IsMember({"u8", "u16", "f32"}));
  c->add_flag("--big-endian", a.big_endian, "Raw input: big-endian samples");
  c->add_option("--octree-error", a.octree_error,
                "Meshes: Leven's adaptive octree instead of the uniform grid: a node splits while "
                "some cell is smaller than its voxels and the field's spread there exceeds E "
                "(field units) or P% of its range; the finest grid (--resolution/--voxel-size) "
                "is never held whole");
  c->add_option("--vertical-levels", a.vertical_levels,
                "WRF input: its uneven levels resampled at their heights (the geopotential of "
                "each step) onto a uniform grid: finest (the thinnest layer's spacing, at most " +
                    std::to_string(tsp::kFinestLevelsCap) +
                    " levels; default), N levels, a spacing such as 50m, or native (the levels "
                    "as stored, at their mean spacing)");
  c->add_flag("--allow-external", a.allow_external,
              "HDF5 input: read its external links, external raw storage and virtual datasets "
              "(other files it names; refused by default)");
}

tsp::SourceOptions source_options(const InputArgs& a, const std::string& field) {
  tsp::SourceOptions so;
  so.field = field;
  if (!a.raw_dims.empty()) so.raw_dims = parse_dims(a.raw_dims, "--raw-dims", kMaxRawEdge, false);
  so.raw_type = a.raw_type == "u8"    ? tsp::RawType::u8
                : a.raw_type == "u16" ? tsp::RawType::u16
                                      : tsp::RawType::f32;
  so.raw_big_endian = a.big_endian;
  so.allow_external = a.allow_external;
  so.plot3d_grid = a.xyz;
  so.vertical = tsp::parse_vertical_levels(a.vertical_levels, "--vertical-levels");
  return so;
}

tsp::VoxelizeOptions voxelize_options(const InputArgs& a, int threads) {
  tsp::VoxelizeOptions vo;
  vo.resolution = a.resolution;
  vo.voxel_size = a.voxel_size;
  vo.cell_data = a.cell_data == "points" ? tsp::CellDataMode::points : tsp::CellDataMode::constant;
  vo.sample.threads = threads;
  vo.sample.kind = a.voxelizer == "scan"         ? tsp::VoxelizerKind::scan
                   : a.voxelizer == "two-buffer" ? tsp::VoxelizerKind::two_buffer
                                                 : tsp::VoxelizerKind::locate;
  vo.sample.hex = a.hex == "tetrahedra" ? tsp::HexSampling::tetrahedra : tsp::HexSampling::isoparametric;
  vo.sample.antialias = a.antialias;
  vo.sample.jitter = a.jitter == "on";
  if (a.antialias != 1 && a.voxelizer == "locate")
    throw tsp::UsageError("--antialias " + std::to_string(a.antialias) +
                          " needs --voxelizer scan or two-buffer (the locating voxelizer samples "
                          "voxel centres)");
  if (a.voxelizer == "scan" && a.antialias > tsp::kMaxAntialias)
    throw tsp::UsageError("--antialias " + std::to_string(a.antialias) + ": --voxelizer scan takes "
                          "1 to " + std::to_string(tsp::kMaxAntialias) + " (two-buffer up to " +
                          std::to_string(tsp::kMaxTwoBufferK) + ")");
  if (a.jitter == "on" && a.voxelizer != "two-buffer")
    throw tsp::UsageError("--jitter on needs --voxelizer two-buffer");
  return vo;
}

std::string input_key(const InputArgs& a) {
  const InputArgs d;
  std::string k;
  const auto add = [&k](const std::string& name, const std::string& value) {
    k += "|" + name + "=" + value;
  };
  if (a.raw_dims != d.raw_dims) add("raw-dims", a.raw_dims);
  if (a.raw_type != d.raw_type) add("raw-type", a.raw_type);
  if (a.big_endian) add("big-endian", "1");
  if (a.resolution != d.resolution) add("resolution", std::to_string(a.resolution));
  if (a.voxel_size != d.voxel_size) add("voxel-size", std::to_string(a.voxel_size));
  if (a.cell_data != d.cell_data) add("cell-data", a.cell_data);
  if (a.voxelizer != d.voxelizer) add("voxelizer", a.voxelizer);
  if (a.hex != d.hex) add("hex", a.hex);
  if (a.antialias != d.antialias) add("antialias", std::to_string(a.antialias));
  if (a.jitter != d.jitter) add("jitter", a.jitter);
  if (a.xyz != d.xyz) add("xyz", a.xyz);
  if (a.octree_error != d.octree_error) add("octree-error", a.octree_error);
  // Always, the default too: a WRF file built before its levels were resampled at their
  // heights (by an older tspplay, the same other options) is not reused.
  add("vertical-levels", a.vertical_levels);
  return k;
}

bool octree_error(const InputArgs& a, tsp::AdaptiveOptions& o) {
  const std::string& s = a.octree_error;
  if (s.empty()) return false;
  const bool percent = s.back() == '%';
  const std::string number = percent ? s.substr(0, s.size() - 1) : s;
  std::size_t used = 0;
  double v = -1;
  try {
    v = std::stod(number, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != number.size() || !std::isfinite(v) || v < 0)
    throw tsp::UsageError("--octree-error " + s +
                          ": expected a threshold >= 0 in the field's units, or P% of its range");
  o.error = percent ? v / 100 : v;
  o.relative = percent;
  return true;
}

}  // namespace tspcli
