// Compositing boxes back to front (spec §7, §9): as view-aligned slice polygons (textured: scalar
// → TF lookup; flat: one premultiplied colour) or as one box each (textured: a ray cast over the
// same slice planes; flat: the exact exponential over the ray's depth through the box), with the
// polygon and cube vertex buffers, the TF lookup texture and the 16-bit render target. Both
// renderers draw through it.
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "gl/context.h"
#include "gl/shader.h"
#include "render/brick_pages.h"
#include "render/brick_textures.h"
#include "render/cpu_pass.h"
#include "render/frame_report.h"
#include "render/image_reuse.h"
#include "render/ray_constants.h"
#include "render/ray_programs.h"
#include "render/render_target.h"
#include "render/surface_splats.h"
#include "render/tf_texture.h"
#include "tsp/clip/probe.h"
#include "tsp/core/types.h"
#include "tsp/frame/camera.h"
#include "tsp/frame/slicing.h"

namespace tspgl {

/// One box of a frame, drawn as a run of consecutive polygons of the frame's soup (slices) or as
/// the box itself (`as_box`).
struct DrawItem {
  int first_polygon = 0, polygon_count = 0;  ///< slices
  BrickSlot slot;       ///< where the samples are (slot.texture 0: a flat item)
  std::array<float, 4> colour{};  ///< premultiplied colour per slice (flat slice items)
  bool as_box = false;  ///< drawn once as a box: ray cast (textured) or exact (flat)
  tsp::Aabb bounds;     ///< the box (box items)
  tsp::Rgba flat;       ///< colour and opacity per voxel of depth (flat box items)
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
  void set_transfer_function(const tsp::TransferFunction& tf, tsp::ValueRange quantized,
                             std::vector<double> prior = {});
  /// Textures carry a stencil in their second channel (RG16): outside samples are not drawn.
  void set_stencil(bool on) { stencil_ = on; }
  /// The one-pass ray caster clips to clip (no probe: nothing clipped) and, with surface, draws
  /// the clip surface opaque in surface's colours (for bricks quantized over `quantized`).
  /// Throws tsp::GlError.
  void set_clip(const tsp::ClipRegion& clip, const tsp::TransferFunction* surface,
                tsp::ValueRange quantized);
  /// The opaque surface under the volume from the next begin_frame on, in frames whose
  /// settings.surface is on (rays compositing; the
  /// tree and TF must outlive its frames): drawn first, the rays end where they meet it; a
  /// frame with a surface is never kept (no partial-image reuse). An empty SurfaceFrame: none.
  void set_surface(const SurfaceFrame& s) { surface_ = s; }
  /// True when a surface is set (a tree with nodes).
  bool has_surface() const { return surface_.tree && !surface_.tree->nodes.empty(); }
  /// What the surface pass of the last begin_frame drew.
  const SurfaceStats& surface_stats() const { return surface_stats_; }
  /// Makes the context current, binds the 16-bit target at the camera's size (cleared unless
  /// `keep`: then the last frame's pixels stay, for partial-image reuse), sets blending and the
  /// camera. Throws tsp::GlError.
  void begin_frame(const tsp::Camera& camera, const RenderSettings& settings, bool keep = false);
  /// Restricts the following draws to rect and clears it to the background (x1 ≤ x0: no
  /// restriction again).
  void set_region(const PixelRect& rect, const RenderSettings& settings);
  /// Uploads the frame's polygons (float vertices) to the vertex buffer.
  void upload(const tsp::PolygonSoup& soup);
  /// Draws items in order (polygons of the last upload(); boxes need no upload).
  void draw(const std::vector<DrawItem>& items);
  /// Uploads pages, the brick grid the one-pass ray caster walks, for a volume of dims (rays
  /// compositing; once per frame, before draw_rays).
  /// With bounds (a union of whole bricks' geometric boxes), the rays are cast through that box
  /// only — what lies outside draws nothing (transparent or clipped bricks).
  void set_pages(const BrickPages& pages, tsp::Dims dims, const tsp::Aabb* bounds = nullptr);
  /// Adaptive sampling (settings.sampling_tol > 0 at begin_frame, no probes): per cell of a
  /// grid of cells covering `cell` voxels each (x fastest), its row of tsp::kStepMultipliers, for
  /// this frame's draw_rays. Ignored when the frame is not adaptive.
  void set_step_map(const std::vector<std::uint8_t>& rows, std::array<int, 3> grid,
                    std::array<int, 3> cell);
  /// True when this frame (since begin_frame) samples adaptively and needs set_step_map.
  bool adaptive() const { return adaptive_; }
  /// Draws the volume box once, ray casting the pages of the last set_pages (once per frame, or
  /// once per set_region with partial-image reuse).
  void draw_rays();
  /// Copies the target to the default framebuffer (at settings.viewport_origin) and waits for
  /// GL; returns the fragments the frame's draws produced that were not discarded
  /// (GL_SAMPLES_PASSED: one per blended slice fragment, one per pixel and box drawn whole).
  /// Throws tsp::GlError.
  std::int64_t end_frame();
  /// The context.
  GlContext& context() { return ctx_; }
  /// The 16-bit target frames are drawn in (the player holds and restores its picture).
  RenderTarget& target() { return target_; }
  /// True when this frame's rays (since begin_frame) are cast on the CPU (settings.backend):
  /// textured pages must then carry their texels in RAM (BrickSlot::host).
  bool cpu_frame() const { return cpu_; }
  /// Why this frame, asked to be cast on the CPU, is drawn by GL (empty: it is not).
  const std::string& backend_note() const { return backend_note_; }
  /// Samples the CPU caster read since begin_frame (0 for GL frames).
  std::int64_t cpu_samples() const { return cpu_samples_; }
  /// True when the context's GL renderer is software (where --backend auto casts on the CPU).
  bool software_gl() const { return software_gl_; }

 private:
  GlContext& ctx_;
  SurfaceFrame surface_;                           // the surface set for the next frames
  std::unique_ptr<SurfaceSplats> surface_splats_;  // its pass (made on first use)
  SurfaceStats surface_stats_;
  bool surface_drawn_ = false;                     // this frame's rays stop at the surface
  tsp::ClipRegion clip_region_;                    // the last set_clip's solid
  const GlApi& gl_;
  Program textured_, flat_, box_textured_, box_flat_;
  RayPrograms ray_programs_;  ///< the caster's variants, each built on first use
  bool clipping_ = false;     ///< set_clip chose a clip variant (probes are set)
  RayVariant clip_variant_ = RayVariant::clipped;  ///< which one
  const Program* rays_ = nullptr;  ///< the caster in use this frame
  bool adaptive_ = false;               ///< this frame samples adaptively
  GLuint step_map_ = 0;                 ///< per leaf brick: multiplier, TF row coordinate
  std::vector<float> step_texels_;
  void set_units(const Program& p);
  bool stencil_ = false;
  GLuint pages_ = 0, fragments_query_ = 0;
  GLuint rays_atlas_ = 0;  ///< the atlas the last set_pages' textured bricks read
  GLuint vao_ = 0, vbo_ = 0, cube_vao_ = 0, cube_vbo_ = 0;
  TfTexture tf_;
  TfTexture surface_tf_;  ///< the clip surface's colours
  bool surface_on_ = false;
  RenderTarget target_;
  std::array<int, 4> output_{};  ///< x, y, width, height of the frame in the default framebuffer
  // The CPU caster (--backend): this frame's choice, its scene and the current region.
  bool software_gl_ = false;
  bool cpu_ = false;
  std::int64_t cpu_samples_ = 0;
  std::string backend_note_;
  CastScene cast_;
  CastRect region_;
  std::unique_ptr<CpuPass> cpu_pass_;  ///< made on first use
  void choose_backend(const RenderSettings& settings, bool plain);
  // begin_frame's parts: the camera's directions and headlight, the surface drawn under the
  // volume, every program's per-frame uniforms and TF tables, the CPU caster's scene.
  struct FrameView {
    std::array<double, 3> dir{}, eye{}, ray{};
    double cosine = 1;
    std::array<double, 3> voxel{}, light{};  ///< voxel sizes (smallest 1), the headlight
  };
  static FrameView frame_view(const tsp::Camera& camera);
  void draw_surface_under(const tsp::Camera& camera, const RenderSettings& settings,
                          const FrameView& f, bool keep);
  void set_frame_uniforms(const tsp::Camera& camera, const RenderSettings& settings,
                          const FrameView& f, bool refine);
  void set_cast_scene(const tsp::Camera& camera, const RenderSettings& settings,
                      const FrameView& f, bool refine);
  std::vector<float> vertices_;
  std::vector<GLint> firsts_;
  std::vector<GLsizei> counts_;
};

}  // namespace tspgl
