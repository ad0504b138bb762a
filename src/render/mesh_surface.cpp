#include "render/mesh_surface.h"

#include <algorithm>
#include <cstdio>

#include "tsp/core/error.h"

#include "tsp/metric/tf_io.h"
#include "tsp/source/open_mesh_source.h"
#include "tsp/surface/boundary.h"

namespace tspgl {

namespace {
// How far a surface mesh may stick out of the file's box, as a fraction of its size.
constexpr double kSurfaceBoxSlack = 0.02;
// The least share of the file's box, per axis, a surface mesh must span.
constexpr double kSurfaceMinSpan = 0.5;
}  // namespace

MeshSurface::MeshSurface(const std::string& input, const std::string& field,
                         const tsp::TspFile& file, const std::string& tf_arg, int first_step)
    : source_(tsp::open_mesh_source(input, field.empty() ? file.metadata().field : field)),
      origin_(file.metadata().origin),
      spacing_(file.metadata().spacing),
      field_(field.empty() ? file.metadata().field : field) {
  check_matches(input, file, first_step);
  // The first step's values; where that step holds one value (a crash test's velocity before
  // the impact), the first later step that holds more, so that the map spans what changes.
  tsp::ValueRange r = tree(first_step).value_range;
  for (int t = first_step + 1; !(r.hi > r.lo) && t < source_->steps(); ++t) {
    const tsp::ValueRange later = tree(t).value_range;
    if (later.hi > later.lo) r = later;
  }
  if (!(r.hi > r.lo)) r = {r.lo - 0.5, r.lo + 0.5};  // one value throughout: any range around it
  tf_ = tsp::transfer_function_from_arg(tf_arg.empty() ? "preset:cool-to-warm" : tf_arg, r,
                                        tsp::kDefaultTfEntries);
}

void MeshSurface::check_matches(const std::string& input, const tsp::TspFile& file,
                                int first_step) {
  const int steps = file.tree().time().steps();
  const std::string both = input + " does not match " + file.path();
  if (source_->steps() != steps)
    throw tsp::UsageError("--surface-mesh " + both + ": the mesh has " +
                          std::to_string(source_->steps()) + " steps, the .tsp file " +
                          std::to_string(steps) + " (give the mesh the file was built from)");
  // The mesh at the first step shown must lie in the file's box (a voxel and a fraction of the
  // box's size to spare, for voxel sizes that do not divide the mesh's) and span a good part of
  // it on every axis: a mesh elsewhere, or much smaller, is another mesh.
  const tsp::Aabb mesh = source_->bounds(std::clamp(first_step, 0, steps - 1));
  const tsp::Aabb& box = file.frame();
  for (int a = 0; a < 3; ++a) {
    const double extent = box.hi[a] - box.lo[a];
    const double spare = 2 * spacing_[std::size_t(a)] + kSurfaceBoxSlack * extent;
    const double mesh_extent = mesh.hi[a] - mesh.lo[a];
    if (mesh.lo[a] < box.lo[a] - spare || mesh.hi[a] > box.hi[a] + spare ||
        mesh_extent < kSurfaceMinSpan * extent - spare) {
      static constexpr const char* kAxis[] = {"x", "y", "z"};
      char text[256];
      std::snprintf(text, sizeof text,
                    ": along %s the mesh spans [%g, %g], the .tsp file's grid [%g, %g] (give the "
                    "mesh the file was built from)",
                    kAxis[a], mesh.lo[a], mesh.hi[a], box.lo[a], box.hi[a]);
      throw tsp::UsageError("--surface-mesh " + both + text);
    }
  }
}

const tsp::SplatTree& MeshSurface::tree(int t) {
  t = std::clamp(t, 0, source_->steps() - 1);
  if (t != step_) {
    const tsp::Mesh mesh = source_->read_step(t);
    tree_ = tsp::build_splat_tree(mesh, tsp::boundary_triangles(mesh), origin_, spacing_);
    step_ = t;
  }
  return tree_;
}

}  // namespace tspgl
