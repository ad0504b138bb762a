#include "render/mesh_surface.h"

#include <algorithm>

#include "tsp/metric/tf_io.h"
#include "tsp/source/open_mesh_source.h"
#include "tsp/surface/boundary.h"

namespace tspgl {

MeshSurface::MeshSurface(const std::string& input, const std::string& field,
                         const tsp::TspFile& file, const std::string& tf_arg, int first_step)
    : source_(tsp::open_mesh_source(input, field.empty() ? file.metadata().field : field)),
      origin_(file.metadata().origin),
      spacing_(file.metadata().spacing) {
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
