// src/render: drawing frames with GL; may include tsp/, gl/.
// A mesh series' boundary as splat hierarchies, one step at a time (TetSplat's Shell under the
// volume: render|play --surface boundary): the mesh read with the field its surface shows, its
// points placed on the volume file's sample grid, coloured by its own TF.
#pragma once
#include <memory>
#include <string>

#include "render/surface_splats.h"
#include "tsp/metric/transfer_function.h"
#include "tsp/source/mesh_source.h"
#include "tsp/store/tsp_file.h"
#include "tsp/surface/splat_tree.h"

namespace tspgl {

/// The boundary splat hierarchy of each step of a mesh series, and its colours. Not
/// thread-safe.
class MeshSurface {
 public:
  /// Opens the mesh series input (any open_mesh_source input) reading field ("": file's field),
  /// placed on file's grid; colours from tf_arg (a TF file or preset:NAME; "": cool-to-warm)
  /// over the surface's values at step first_step (or the first later step holding more than
  /// one value). Throws IoError/FormatError naming the input
  /// or the TF file, UsageError for a field the mesh lacks.
  MeshSurface(const std::string& input, const std::string& field, const tsp::TspFile& file,
              const std::string& tf_arg, int first_step);
  /// The hierarchy of step t (clamped to the series; the last step's is kept). Throws
  /// IoError/FormatError naming the input.
  const tsp::SplatTree& tree(int t);
  /// What the compositor draws for step t with a minimum splat size of min_px (the tree of
  /// step t and the colours; valid until the next call). Throws like tree().
  SurfaceFrame frame(int t, double min_px) { return {&tree(t), &tf_, min_px}; }
  /// The surface's colours (what its legend bar shows).
  const tsp::TransferFunction& tf() const { return tf_; }
  /// The field the surface shows (its legend's title: "surface: FIELD").
  const std::string& field() const { return field_; }

 private:
  /// Refuses (tsp::UsageError naming both files) a mesh whose steps differ from file's, or whose
  /// box at first_step lies outside file's grid or spans much less of it.
  void check_matches(const std::string& input, const tsp::TspFile& file, int first_step);

  std::unique_ptr<tsp::MeshSource> source_;
  std::array<double, 3> origin_, spacing_;
  int step_ = -1;
  tsp::SplatTree tree_;
  tsp::TransferFunction tf_;
  std::string field_;
};

}  // namespace tspgl
