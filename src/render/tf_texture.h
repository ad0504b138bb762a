// The transfer function as the renderer samples it: a 1-D lookup texture holding, per entry, the
// colour premultiplied by the opacity corrected for the slice spacing (spec §9), with nearest
// lookup so the rendered TF is exactly the K-entry table the metrics reason about.
#pragma once
#include <vector>

#include "gl/gl_api.h"
#include "tsp/core/types.h"
#include "tsp/metric/transfer_function.h"

namespace tspgl {

/// One lookup texture of a GL context. Use from the context's thread with it current.
class TfTexture {
 public:
  /// Creates the texture object (empty until the first bind()).
  explicit TfTexture(const GlApi& gl);
  /// Deletes it.
  ~TfTexture();
  TfTexture(const TfTexture&) = delete;
  TfTexture& operator=(const TfTexture&) = delete;

  /// Uses tf for bricks quantized over `quantized` from the next bind() on; prior (per entry,
  /// how many samples take its value; empty: none) weighs the coarse levels' blur
  /// (tsp::blurred_entries).
  void set(const tsp::TransferFunction& tf, tsp::ValueRange quantized,
           std::vector<double> prior = {});
  /// Binds it to texture unit `unit`, re-uploading first when the TF or spacing changed.
  /// Throws tsp::GlError.
  void bind(int unit, double spacing);
  /// Binds the pre-integrated K × K table for segments of `spacing` voxels (tsp::preintegrate)
  /// to texture unit `unit`, recomputing it first when the TF or spacing changed (O(K³) on the
  /// CPU: tens of ms for K = 256). Throws tsp::GlError.
  void bind_preintegrated(int unit, double spacing);
  /// Binds the K × R table of adaptive sampling (tsp/frame/sample_steps.h) to texture unit
  /// `unit`: row r is the lookup of bind() for a spacing of spacing·tsp::kStepMultipliers[r];
  /// re-uploads first when the TF or spacing changed. Throws tsp::GlError.
  void bind_rows(int unit, double spacing);
  /// Binds the K × tsp::kLevelTfRows table of coarse LOD levels (tsp/metric/level_tf.h) to
  /// texture unit `unit`: row r is the lookup of bind() for the TF blurred by
  /// tsp::level_tf_sigma(r); re-uploads first when the TF or spacing changed. Throws
  /// tsp::GlError.
  void bind_levels(int unit, double spacing);
  /// Binds refinement's K × 2 table (volume_ray.frag, TSP_REFINE) to texture unit `unit`: row 0
  /// the lookup of bind() with each entry's piece (tsp::tf_pieces at spacing and tol) packed
  /// into its opacity as α + 2·piece, row 1 the lookup of bind() for a spacing of
  /// spacing / samples; re-uploads first when the TF, spacing or tol changed. Throws
  /// tsp::GlError.
  void bind_refine(int unit, double spacing, int samples, double tol);
  /// Binds the TF's colours, opaque and not premultiplied (a probe surface's lookup), to
  /// texture unit `unit`, re-uploading first when the TF changed. Throws tsp::GlError.
  void bind_opaque(int unit);
  /// The RGBA floats bind() uploaded last (K entries): what the CPU ray caster reads.
  const std::vector<float>& point_rgba() const { return point_rgba_; }
  /// The K × 2 RGBA floats bind_refine() uploaded last.
  const std::vector<float>& refine_rgba() const { return refine_rgba_; }
  /// The K × tsp::kLevelTfRows RGBA floats bind_levels() uploaded last.
  const std::vector<float>& levels_rgba() const { return levels_rgba_; }
  /// Entries of the TF (K).
  int size() const { return tf_.size(); }
  /// TF coordinate = normalised code · scale + offset (the shader's tf_map).
  float scale() const { return float(scale_); }
  /// See scale().
  float offset() const { return float(offset_); }

 private:
  const GlApi& gl_;
  GLuint id_ = 0, table_id_ = 0, rows_id_ = 0, levels_id_ = 0, refine_id_ = 0;
  double scale_ = 1, offset_ = 0;
  double spacing_ = -1;             ///< spacing the texture was corrected for (−1: stale)
  double table_spacing_ = -1;       ///< spacing the pre-integrated table was made for
  double rows_spacing_ = -1;        ///< spacing the adaptive rows were made for
  double levels_spacing_ = -1;      ///< spacing the level rows were made for
  double refine_spacing_ = -1;      ///< spacing refinement's lookups were made for
  double refine_tol_ = -1;          ///< tolerance refinement's pieces were cut with
  bool opaque_current_ = false;     ///< the opaque colours are uploaded (bind_opaque)
  tsp::TransferFunction tf_;        ///< the TF as given (uncorrected, not premultiplied)
  std::vector<double> prior_;       ///< per entry, the data's count there (empty: none)
  std::vector<float> point_rgba_, refine_rgba_, levels_rgba_;  ///< as last uploaded
};

}  // namespace tspgl
