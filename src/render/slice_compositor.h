// Compositing view-aligned slice polygons back to front (spec §7, §9): the two slice programs
// (textured: scalar → TF lookup; flat: one premultiplied colour), the polygon vertex buffer, the
// TF lookup texture and the 16-bit render target. Both renderers draw through it.
#pragma once
#include <array>
#include <vector>

#include "gl/context.h"
#include "gl/shader.h"
#include "render/frame_report.h"
#include "render/render_target.h"
#include "render/tf_texture.h"
#include "tsp/core/types.h"
#include "tsp/frame/camera.h"
#include "tsp/frame/slicing.h"

namespace tspgl {

/// A run of consecutive polygons of the frame's soup drawn one way.
struct DrawItem {
  int first_polygon = 0, polygon_count = 0;
  GLuint texture = 0;   ///< 3-D scalar texture, or 0 for a flat item
  tsp::Box samples;     ///< the samples the texture holds (textured items)
  std::array<float, 4> colour{};  ///< premultiplied colour (flat items)
};

/// The premultiplied colour of a flat slice of c for slice spacing `spacing`. Never throws.
std::array<float, 4> flat_colour(const tsp::Rgba& c, double spacing);

/// Slice compositing in one GL context (which must be current and outlive it). Use from the
/// context's thread; not copyable.
class SliceCompositor {
 public:
  /// Builds the programs and buffers. Throws tsp::GlError, tsp::IoError (shader files).
  explicit SliceCompositor(GlContext& ctx);
  /// Deletes the buffers.
  ~SliceCompositor();
  SliceCompositor(const SliceCompositor&) = delete;
  SliceCompositor& operator=(const SliceCompositor&) = delete;

  /// Uses tf for bricks quantized over `quantized` from the next frame on.
  void set_transfer_function(const tsp::TransferFunction& tf, tsp::ValueRange quantized);
  /// Makes the context current, binds and clears the 16-bit target, sets blending and the
  /// camera. Throws tsp::GlError.
  void begin_frame(const tsp::Camera& camera, const RenderSettings& settings);
  /// Uploads the frame's polygons (float vertices) to the vertex buffer.
  void upload(const tsp::PolygonSoup& soup);
  /// Draws items in order (polygons of the last upload()).
  void draw(const std::vector<DrawItem>& items);
  /// Copies the target to the default framebuffer and waits for GL. Throws tsp::GlError.
  void end_frame();
  /// The context.
  GlContext& context() { return ctx_; }

 private:
  GlContext& ctx_;
  const GlApi& gl_;
  Program textured_, flat_;
  GLuint vao_ = 0, vbo_ = 0;
  TfTexture tf_;
  RenderTarget target_;
  std::vector<float> vertices_;
  std::vector<GLint> firsts_;
  std::vector<GLsizei> counts_;
};

}  // namespace tspgl
