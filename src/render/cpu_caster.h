// The one-pass ray caster on the CPU (--backend cpu): the same walk over the same brick pages as
// shaders/volume_ray.frag's segment caster (empty leaps, flat bricks' exact exponential,
// full-resolution bricks in the slice planes' segments with refinement, LOD level bricks with
// their TF rows, Blinn–Phong with the neighbour brick's taps), on textures kept in RAM
// (host_volume.h), in tiles over tsp::parallel_for. GL-free: the compositor hands it a
// CastScene and blends its picture into the frame (slice_compositor.h).
// What it does not draw (clip probes, pre-integration, adaptive sampling, a surface under the
// volume, slices and boxes compositing) is named by cpu_unsupported() and drawn by GL.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "render/host_volume.h"

namespace tspgl {

/// The transfer-function tables the GL caster reads as textures, as RGBA floats (K entries a
/// row; nearest lookup at tf coordinate u: entry floor(u·K) clamped).
struct CastTables {
  int entries = 0;                 ///< K
  const float* point = nullptr;    ///< the spacing-corrected premultiplied lookup (K)
  const float* refine = nullptr;   ///< refinement's two rows (K × 2), null: no refinement
  const float* levels = nullptr;   ///< the coarse levels' rows (K × tsp::kLevelTfRows)
  float scale = 1, offset = 0;     ///< tf coordinate = normalised code · scale + offset
};

/// Everything one cast of the pages needs: the frame's camera, the pages and their texels, the
/// TF tables and the sampling settings (the uniforms of volume_ray.frag).
struct CastScene {
  std::array<int, 3> grid{};       ///< bricks per axis
  std::array<int, 3> cell{};       ///< sample spacings a brick covers per axis
  const float* pages = nullptr;    ///< 4 floats per brick (BrickPages::texels())
  const HostVolume* volume = nullptr;  ///< what textured pages read (null: none textured)
  glm::vec3 box_lo{0}, box_hi{0};  ///< the box the rays are cast through, sample coordinates
  glm::dmat4 inverse_view_projection{1};  ///< clip space → sample coordinates
  glm::vec3 view_dir{0, 0, 1};     ///< slice planes' normal over the central ray's cosine
  glm::vec3 ray_dir{0, 0, 1};      ///< orthographic rays
  glm::vec3 eye{0};                ///< perspective rays' origin
  bool perspective = false;
  int width = 0, height = 0;       ///< the render target in pixels
  float spacing = 0.5f;            ///< sample spacing in voxels
  bool stencil = false;            ///< texels carry a stencil (second channel)
  /// Every full-resolution page reads one dense region (BrickPages::runs): a ray walks each run
  /// of such bricks as one volume.
  bool runs = false;
  bool shade = false;              ///< Blinn–Phong headlight
  glm::vec4 phong{0};              ///< ambient, diffuse, specular, power
  glm::vec3 light_dir{0, 0, 1};    ///< unit, towards the viewer
  glm::vec3 inv_voxel{1};          ///< 1 / voxel size per axis (smallest 1)
  CastTables tf;
};

/// A rectangle of target pixels [x0, x1) × [y0, y1), y up (GL window coordinates).
struct CastRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

/// What one cast did.
struct CastStats {
  std::int64_t pixels = 0;   ///< pixels drawn (rays that composited something)
  std::int64_t samples = 0;  ///< scalar samples read through a TF (the work a frame costs)
};

/// Casts the rays of the pixels in rect (clamped to the target) into rgba: width × height × 4
/// premultiplied floats, rows bottom-up as GL reads them; a pixel whose ray draws nothing gets
/// alpha 0 (and is left out, like a discarded fragment). Pixels outside rect are not touched.
/// Uses `threads` workers (0: all). Never throws but std::bad_alloc; thread-safe for distinct
/// outputs (scene is read only).
CastStats cast_rays(const CastScene& scene, const CastRect& rect, int threads,
                    std::vector<float>& rgba);

}  // namespace tspgl
