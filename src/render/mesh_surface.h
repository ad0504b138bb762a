// src/render: drawing frames with GL; may include tsp/, gl/.
// A mesh series' boundary as splat hierarchies, one step at a time (TetSplat's Shell under the
// volume: render|play --surface boundary): the mesh read with the field its surface shows, its
// points placed on the volume's sample grid.
#pragma once
#include <array>
#include <memory>
#include <string>

#include "tsp/source/mesh_source.h"
#include "tsp/surface/splat_tree.h"

namespace tspgl {

/// The boundary splat hierarchy of each step of a mesh series. Not thread-safe.
class MeshSurface {
 public:
  /// Opens the mesh series input (any open_mesh_source input) reading field (empty: the
  /// reader's default) for a volume whose voxel (0, 0, 0) lies at origin with the given spacing.
  /// Throws IoError/FormatError naming the input, UsageError for a field it lacks.
  MeshSurface(const std::string& input, const std::string& field,
              const std::array<double, 3>& origin, const std::array<double, 3>& spacing);
  /// Steps of the series.
  int steps() const;
  /// The hierarchy of step t (clamped to the series; the last step's is kept). Throws
  /// IoError/FormatError naming the input.
  const tsp::SplatTree& tree(int t);
  /// The input, as given.
  const std::string& input() const { return input_; }

 private:
  std::string input_;
  std::unique_ptr<tsp::MeshSource> source_;
  std::array<double, 3> origin_, spacing_;
  int step_ = -1;
  tsp::SplatTree tree_;
};

}  // namespace tspgl
