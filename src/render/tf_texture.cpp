#include "render/tf_texture.h"

#include <algorithm>
#include <cmath>
#include <span>

#include "tsp/frame/refine.h"
#include "tsp/frame/sample_steps.h"
#include "tsp/metric/level_tf.h"
#include "tsp/metric/preintegration.h"

namespace tspgl {

namespace {

// Appends entries premultiplied, their opacity corrected for `spacing` voxels (spec §9): the
// lookup every TF texture holds.
void append_corrected(std::vector<float>& rgba, std::span<const tsp::Rgba> entries,
                      double spacing) {
  for (const tsp::Rgba& e : entries) {
    const float a = tsp::corrected_opacity(e.a, spacing);
    rgba.insert(rgba.end(), {e.r * a, e.g * a, e.b * a, a});
  }
}

// Uploads `rows` rows of k RGBA floats to the bound 2-D texture, nearest and clamped.
void upload_rows(const GlApi& gl, const std::vector<float>& rgba, int k, int rows,
                 const char* what) {
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, GLsizei(k), GLsizei(rows), 0, GL_RGBA, GL_FLOAT,
                rgba.data());
  check_gl(gl, what);
}

// The 1-D table of k entries, nearest and clamped, into the bound GL_TEXTURE_1D.
void upload_table(const GlApi& gl, const std::vector<float>& rgba, int k, const char* what) {
  gl.TexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl.TexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl.TexParameteri(GL_TEXTURE_1D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl.TexImage1D(GL_TEXTURE_1D, 0, GL_RGBA32F, GLsizei(k), 0, GL_RGBA, GL_FLOAT, rgba.data());
  check_gl(gl, what);
}

}  // namespace

TfTexture::TfTexture(const GlApi& gl) : gl_(gl) {
  gl_.GenTextures(1, &id_);
  gl_.GenTextures(1, &table_id_);
  gl_.GenTextures(1, &rows_id_);
  gl_.GenTextures(1, &levels_id_);
  gl_.GenTextures(1, &refine_id_);
}

TfTexture::~TfTexture() {
  gl_.DeleteTextures(1, &id_);
  gl_.DeleteTextures(1, &table_id_);
  gl_.DeleteTextures(1, &rows_id_);
  gl_.DeleteTextures(1, &levels_id_);
  gl_.DeleteTextures(1, &refine_id_);
}

void TfTexture::set(const tsp::TransferFunction& tf, tsp::ValueRange quantized,
                    std::vector<double> prior) {
  tf_ = tf;
  prior_ = std::move(prior);
  spacing_ = -1;  // re-uploaded, corrected for the spacing, by the next bind
  table_spacing_ = -1;
  rows_spacing_ = -1;
  levels_spacing_ = -1;
  refine_spacing_ = -1;
  refine_tol_ = -1;
  opaque_current_ = false;
  // A normalised code s means v = q.lo + s·q.width; its TF coordinate is (v − tf.lo)/tf.width.
  const tsp::ValueRange d = tf.domain();
  scale_ = quantized.width() / d.width();
  offset_ = (quantized.lo - d.lo) / d.width();
}

void TfTexture::bind(int unit, double spacing) {
  gl_.ActiveTexture(GLenum(GL_TEXTURE0 + unit));
  gl_.BindTexture(GL_TEXTURE_1D, id_);
  if (spacing == spacing_) return;
  std::vector<float>& rgba = point_rgba_;
  rgba.clear();
  rgba.reserve(std::size_t(tf_.size()) * 4);
  append_corrected(rgba, tf_.entries(), spacing);
  upload_table(gl_, rgba, tf_.size(), "uploading the transfer function");
  spacing_ = spacing;
}

void TfTexture::bind_rows(int unit, double spacing) {
  gl_.ActiveTexture(GLenum(GL_TEXTURE0 + unit));
  gl_.BindTexture(GL_TEXTURE_2D, rows_id_);
  if (spacing == rows_spacing_) return;
  std::vector<float> rgba;
  rgba.reserve(std::size_t(tf_.size()) * 4 * tsp::kStepMultipliers.size());
  for (double m : tsp::kStepMultipliers) append_corrected(rgba, tf_.entries(), spacing * m);
  upload_rows(gl_, rgba, tf_.size(), int(tsp::kStepMultipliers.size()),
              "uploading the adaptive sampling's transfer functions");
  rows_spacing_ = spacing;
}

void TfTexture::bind_levels(int unit, double spacing) {
  gl_.ActiveTexture(GLenum(GL_TEXTURE0 + unit));
  gl_.BindTexture(GL_TEXTURE_2D, levels_id_);
  if (spacing == levels_spacing_) return;
  std::vector<float>& rgba = levels_rgba_;
  rgba.clear();
  rgba.reserve(std::size_t(tf_.size()) * 4 * tsp::kLevelTfRows);
  for (int row = 0; row < tsp::kLevelTfRows; ++row)
    append_corrected(rgba, tsp::blurred_entries(tf_, tsp::level_tf_sigma(row), prior_), spacing);
  upload_rows(gl_, rgba, tf_.size(), tsp::kLevelTfRows,
              "uploading the coarse levels' transfer functions");
  levels_spacing_ = spacing;
}

void TfTexture::bind_refine(int unit, double spacing, int samples, double tol) {
  gl_.ActiveTexture(GLenum(GL_TEXTURE0 + unit));
  gl_.BindTexture(GL_TEXTURE_2D, refine_id_);
  if (spacing == refine_spacing_ && tol == refine_tol_) return;
  // Row 0: the point lookup with each entry's piece packed into its opacity, α + 2·piece (a
  // float keeps the opacity to 2⁻¹⁵ with the 256 pieces of a 256-entry TF at most, 2⁻¹⁰ with
  // 4096). Row 1: the lookup for the fine step.
  const std::vector<int> pieces = tsp::tf_pieces(tf_, spacing, tol);
  std::vector<float>& rgba = refine_rgba_;
  rgba.clear();
  rgba.reserve(std::size_t(tf_.size()) * 8);
  append_corrected(rgba, tf_.entries(), spacing);
  for (std::size_t i = 0; i < pieces.size(); ++i) rgba[4 * i + 3] += 2.f * float(pieces[i]);
  append_corrected(rgba, tf_.entries(), spacing / samples);
  upload_rows(gl_, rgba, tf_.size(), 2, "uploading the refinement's transfer functions");
  refine_spacing_ = spacing;
  refine_tol_ = tol;
}

void TfTexture::bind_opaque(int unit) {
  gl_.ActiveTexture(GLenum(GL_TEXTURE0 + unit));
  gl_.BindTexture(GL_TEXTURE_1D, id_);
  if (opaque_current_) return;
  std::vector<float> rgba;
  rgba.reserve(std::size_t(tf_.size()) * 4);
  for (const tsp::Rgba& e : tf_.entries()) rgba.insert(rgba.end(), {e.r, e.g, e.b, 1.f});
  upload_table(gl_, rgba, tf_.size(), "uploading the surface transfer function");
  opaque_current_ = true;
}

void TfTexture::bind_preintegrated(int unit, double spacing) {
  gl_.ActiveTexture(GLenum(GL_TEXTURE0 + unit));
  gl_.BindTexture(GL_TEXTURE_2D, table_id_);
  if (spacing == table_spacing_) return;
  const std::vector<tsp::Rgba> table = tsp::preintegrate(tf_, spacing);
  const int k = tf_.size();
  // Nearest, like the 1-D table: a segment within one entry gets exactly that entry's colour, so
  // the picture converges to the metrics' K-entry table as the spacing shrinks (linear filtering
  // would blend neighbouring entries: a smoother TF than the one the reference draws).
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, k, k, 0, GL_RGBA, GL_FLOAT, table.data());
  check_gl(gl_, "uploading the pre-integrated transfer function");
  table_spacing_ = spacing;
}

}  // namespace tspgl
