// src/render: drawing frames with GL; may include tsp/, gl/.
// The opaque surface under a frame's volume (TetSplat's Shell, tsp/surface): a cut of the splat
// hierarchy drawn as lit discs into a target of its own — colour, and depth along the view as
// the one-pass ray caster measures it — which the compositor copies under the volume and the
// caster stops at (rays end where they meet the surface).
#pragma once
#include <array>
#include <vector>

#include "gl/context.h"
#include "gl/shader.h"
#include "render/tf_texture.h"
#include "tsp/clip/probe.h"
#include "tsp/frame/camera.h"
#include "tsp/metric/transfer_function.h"
#include "tsp/surface/splat_tree.h"

namespace tspgl {

/// A frame's surface: the splat hierarchy (sample coordinates), the TF its field is coloured
/// by (over the TF's own domain) and the minimum splat size of its cut.
struct SurfaceFrame {
  const tsp::SplatTree* tree = nullptr;  ///< null or empty: no surface
  const tsp::TransferFunction* tf = nullptr;  ///< colours (opacity unused); must be set
  double min_px = 1;                     ///< the cut's minimum splat size in pixels
};

/// What a surface pass drew.
struct SurfaceStats {
  int splats = 0;        ///< splats of the cut drawn
  double cut_ms = 0;     ///< choosing the cut and filling the instance buffer
  double ms = 0;         ///< the whole pass: the cut, the draw and GL finishing it
};

/// The splat pass of one GL context (which must be current and outlive it). Use from the
/// context's thread; not copyable.
class SurfaceSplats {
 public:
  /// Builds the program and buffers. Throws tsp::GlError, tsp::IoError (shader files).
  explicit SurfaceSplats(GlContext& ctx);
  /// Deletes them.
  ~SurfaceSplats();
  SurfaceSplats(const SurfaceSplats&) = delete;
  SurfaceSplats& operator=(const SurfaceSplats&) = delete;

  /// Draws s's cut for camera into the pass's own target (width × height, cleared to
  /// background and to no depth), splats whose centre clip removes left out; lit when shade,
  /// with the caster's headlight (light, world axes), voxel scale (inv_voxel) and depth measure
  /// (view_dir). Leaves that target bound for reading. Throws tsp::GlError.
  SurfaceStats draw(const SurfaceFrame& s, const tsp::Camera& camera, const tsp::ClipRegion& clip,
                    int width, int height, const std::array<float, 3>& background, bool shade,
                    const std::array<double, 3>& light, const std::array<double, 3>& inv_voxel,
                    const std::array<double, 3>& view_dir);
  /// The framebuffer the last draw wrote (colour attachment 0: the picture).
  GLuint framebuffer() const { return fbo_; }
  /// The R32F texture of the last draw's depths along the view (1e30 where no splat).
  GLuint depth_texture() const { return depth_tex_; }

 private:
  void resize(int width, int height);

  GlContext& ctx_;
  const GlApi& gl_;
  Program program_;
  TfTexture tf_;
  const tsp::TransferFunction* tf_source_ = nullptr;
  std::uint64_t tf_version_ = ~std::uint64_t(0);
  GLuint vao_ = 0, vbo_ = 0, fbo_ = 0, colour_ = 0, depth_tex_ = 0, depth_rb_ = 0;
  int width_ = 0, height_ = 0;
  std::vector<float> instances_;  // per splat: centre, normal, radius, value, leaf, corners
};

}  // namespace tspgl
