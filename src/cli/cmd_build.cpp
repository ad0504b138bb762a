// tspplay build INPUT -o OUT.tsp: bricks and TSP tree from a time series.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "cli/args.h"
#include "cli/build_runner.h"
#include "cli/commands.h"
#include "cli/input_options.h"
#include "tsp/build/build.h"
#include "tsp/core/error.h"
#include "tsp/source/open_mesh_source.h"
#include "tsp/voxelize/open_fields.h"
#include "tsp/voxelize/open_input.h"
#include "tsp/store/tsp_file.h"

namespace tspcli {
namespace {

struct BuildArgs {
  std::string input, output, field, range;
  InputArgs in;   // how the input is read (shared with play)
  int brick = 0;  // 0: tsp::default_brick_size of the grid
  int threads = 0;
  std::string spacing, origin;
  std::string compress = "none";
};

// build MESH --octree-error E: Leven's adaptive octree instead of the uniform grid.
void run_adaptive_build(const BuildArgs& a, const tsp::BuildOptions& bo) {
  if (a.field.find(',') != std::string::npos)
    throw tsp::UsageError("--octree-error builds one field; --field " + a.field + " names several");
  if (!a.spacing.empty() || !a.origin.empty())
    throw tsp::UsageError("--octree-error: the grid comes from the mesh; --spacing/--origin do not apply");
  const tsp::SourceOptions so = source_options(a.in, a.field);
  if (!tsp::is_mesh_input(a.input, so.allow_external))
    throw tsp::UsageError("--octree-error: " + a.input +
                          " is not an unstructured mesh (.vtu/.vtm/.pvd/.series, VTKHDF "
                          "UnstructuredGrid); regular grids are built without it");
  tsp::AdaptiveOptions ao;
  octree_error(a.in, ao);
  ao.voxelize = voxelize_options(a.in, a.threads);
  ao.build = bo;
  auto source = tsp::open_mesh_source(a.input, so.field, so.allow_external, so.plot3d_grid);
  const tsp::AdaptiveReport r = build_adaptive_with_progress(*source, a.output, ao);
  print_adaptive_summary(a.output, r);
}

// --compress none|deflate[:L] → the deflate level (0: none). Throws UsageError.
int deflate_level(const std::string& s) {
  constexpr int kDefaultDeflate = 4;
  if (s == "none") return 0;
  if (s == "deflate") return kDefaultDeflate;
  if (s.size() == 9 && s.rfind("deflate:", 0) == 0 && s[8] >= '1' && s[8] <= '9') return s[8] - '0';
  throw tsp::UsageError("--compress " + s + ": expected none, deflate or deflate:L with L in 1..9");
}

void run_build(const BuildArgs& a) {
  const tsp::SourceOptions so = source_options(a.in, a.field);

  tsp::BuildOptions bo;
  bo.brick_size = a.brick;
  bo.threads = a.threads;
  bo.field_name = a.field;
  bo.deflate = deflate_level(a.compress);
  if (!a.range.empty()) bo.range = parse_range(a.range, "--range");
  if (!a.spacing.empty()) bo.spacing = parse_triple(a.spacing, "--spacing", "DX,DY,DZ");
  if (!a.origin.empty()) bo.origin = parse_triple(a.origin, "--origin", "X,Y,Z");
  if (!a.in.octree_error.empty()) return run_adaptive_build(a, bo);
  const tsp::VoxelizeOptions vo = voxelize_options(a.in, a.threads);
  // --field A,B,C: several fields, one tree each, in one file.
  const std::vector<std::string> fields = tsp::field_names(a.field);
  if (!fields.empty()) {
    // An HDF5 file is opened once for all of them, and every name checked first.
    const tsp::FieldOpener open_field = tsp::open_input_fields(a.input, so, vo, fields);
    // The first field, opened now, sets the default brick size; the build then takes it.
    std::unique_ptr<tsp::VolumeSource> first = open_field(fields[0]);
    if (bo.brick_size == 0) bo.brick_size = tsp::default_brick_size(first->dims());
    auto open_with_first = [&](const std::string& field) {
      return first ? std::move(first) : open_field(field);
    };
    const std::vector<tsp::BuildReport> reports =
        build_fields_with_progress(open_with_first, fields, a.output, bo);
    if (!build_writes_output()) return;  // rank 0 of tspplay-mpi reports
    for (std::size_t k = 0; k < fields.size(); ++k)
      std::printf("field %s: value range [%g, %g], %.1f MB in %.2f s\n", fields[k].c_str(),
                  reports[k].value_range.lo, reports[k].value_range.hi,
                  double(reports[k].source_bytes) / 1e6, reports[k].seconds);
    print_build_summary(a.output, reports.front());
    return;
  }
  auto source = tsp::open_input(a.input, so, vo);
  if (bo.brick_size == 0) bo.brick_size = tsp::default_brick_size(source->dims());
  tsp::BuildReport r = build_with_progress(*source, a.output, bo);
  if (build_writes_output()) print_build_summary(a.output, r);
}

const CommandRegistrar reg(10, [](CLI::App& app) {
  auto* c = app.add_subcommand("build", "Build a .tsp file (bricks + TSP tree with statistics)");
  auto a = std::make_shared<BuildArgs>();
  c->add_option("input", a->input,
                "Time series: .h5/.nc/.hdf, .pvd/.vti.series/.vti, raw pattern; unstructured: "
                ".vtu/.vtm/.pvd/.vtm.series, VTKHDF UnstructuredGrid (one, transient, or 'can_%d.hdf')")
      ->required();
  c->add_option("-o,--output", a->output, "The .tsp file to write")->required();
  c->add_option("--field", a->field,
                "Field (dataset/variable/array) to read; meshes: NAME, NAME:mag or NAME:x|y|z; "
                "A,B,C: several fields, one tree each, in one file (render/play --field picks one)");
  add_input_options(c, a->in);
  c->add_option("--brick", a->brick, "Brick edge in samples, a power of two 8..64 (default: the one nearest a quarter of "
                "the longest grid edge, in [8, 64]: 16 for 64^3, 32 for 128^3)");
  c->add_option("--range", a->range, "Quantization range LO:HI (default: the data's range)");
  c->add_option("--spacing", a->spacing,
                "DX,DY,DZ: the physical voxel size, instead of what the input says (render and "
                "play show the volume in these proportions)");
  c->add_option("--origin", a->origin, "X,Y,Z: the physical position of voxel (0,0,0)");
  c->add_option("--compress", a->compress,
                "Brick chunks: none (default), deflate (level 4) or deflate:L, L 1..9 (byte "
                "shuffle + deflate; smaller files, slower builds; for playback from slow disks)");
  c->add_option("--threads", a->threads, "Worker threads (default: all cores)");
  c->callback([a] { run_build(*a); });
});

}  // namespace
}  // namespace tspcli
