#include "render/mesh_surface.h"

#include <algorithm>

#include "tsp/source/open_mesh_source.h"
#include "tsp/surface/boundary.h"

namespace tspgl {

MeshSurface::MeshSurface(const std::string& input, const std::string& field,
                         const std::array<double, 3>& origin, const std::array<double, 3>& spacing)
    : input_(input), source_(tsp::open_mesh_source(input, field)), origin_(origin), spacing_(spacing) {}

int MeshSurface::steps() const { return source_->steps(); }

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
