// One ray's walk over the brick grid for the CPU caster (cpu_caster.h): the ray through a pixel
// and the walk's state and steps, as volume_ray.frag's main() (without clip code) walks it. Used
// by cpu_caster.cpp (the walk, the plain segments) and cpu_refine.h (refinement's passes).
// Internal: include only from those.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "render/cpu_batch.h"
#include "render/cpu_sample.h"
#include "tsp/frame/refine.h"

namespace tspgl::detail {

using glm::ivec3;
using glm::vec3;
using glm::vec4;

/// Refinement's rows: the point lookup with pieces packed into opacity, and the fine step.
inline constexpr int kPieceRow = 0, kFineRow = 1;

inline float piece_of(vec4 e) { return std::floor(e.a * 0.5f); }

// The ray through a pixel: where it leaves the box (the fragment's exit_point), and its span in
// depth (box_ray.glsl's ray_span).
struct Ray {
  vec3 dir{0};
  vec3 entry{0};
  float cos_theta = 1, depth_entry = 0, len = 0;
};

// False when the pixel's line of sight misses the box between the near and far planes (no
// fragment of the box's back faces covers its centre).
inline bool pixel_ray(const CastScene& s, int px, int py, Ray& r) {
  const double nx = (px + 0.5) / s.width * 2 - 1, ny = (py + 0.5) / s.height * 2 - 1;
  glm::dvec4 a = s.inverse_view_projection * glm::dvec4(nx, ny, -1, 1);
  glm::dvec4 b = s.inverse_view_projection * glm::dvec4(nx, ny, 1, 1);
  const glm::dvec3 p0 = glm::dvec3(a) / a.w, p1 = glm::dvec3(b) / b.w, d = p1 - p0;
  double t0 = -1e300, t1 = 1e300;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(d[i]) < 1e-300) {
      if (p0[i] < s.box_lo[i] || p0[i] > s.box_hi[i]) return false;
      continue;
    }
    double ta = (s.box_lo[i] - p0[i]) / d[i], tb = (s.box_hi[i] - p0[i]) / d[i];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  if (t1 < t0 || t1 < 0 || t1 > 1) return false;
  const vec3 exit(p0 + d * t1);
  r.dir = s.perspective ? glm::normalize(exit - s.eye) : s.ray_dir;
  const vec3 sgn(r.dir.x + 1e-30f >= 0 ? 1.f : -1.f, r.dir.y + 1e-30f >= 0 ? 1.f : -1.f,
                 r.dir.z + 1e-30f >= 0 ? 1.f : -1.f);
  const vec3 inv = 1.f / glm::max(glm::abs(r.dir), vec3(1e-12f)) * sgn;
  const vec3 far_t = glm::max((exit - s.box_lo) * inv, (exit - s.box_hi) * inv);
  float t = std::min({far_t.x, far_t.y, far_t.z});
  if (s.perspective) t = std::min(t, glm::length(exit - s.eye));
  t = std::max(t, 0.f);
  r.cos_theta = std::max(glm::dot(r.dir, s.view_dir), 1e-6f);
  const float depth_exit = glm::dot(exit, s.view_dir);
  r.depth_entry = depth_exit - t * r.cos_theta;
  r.len = (depth_exit - r.depth_entry) / r.cos_theta;
  r.entry = exit - r.dir * r.len;
  return r.len > 0;
}

inline vec4 page_at(const CastScene& s, ivec3 c) {
  const float* p =
      s.pages + 4 * (std::size_t(c.x) + std::size_t(s.grid[0]) *
                                            (std::size_t(c.y) + std::size_t(s.grid[1]) * std::size_t(c.z)));
  return {p[0], p[1], p[2], p[3]};
}

inline bool inside(const CastScene& s, ivec3 c) {
  return c.x >= 0 && c.y >= 0 && c.z >= 0 && c.x < s.grid[0] && c.y < s.grid[1] &&
         c.z < s.grid[2];
}

inline bool level0_textured(vec4 page) {
  return page.w > 0.5f && ((int(page.w + 0.5f) - 1) & (kClipFlag - 1)) == 0;
}

// The DDA's step to the next brick along the ray: across the nearest face.
inline void step(ivec3& c, vec3& t_max, ivec3 dir, vec3 t_delta) {
  if (t_max.x <= t_max.y && t_max.x <= t_max.z) {
    c.x += dir.x;
    t_max.x += t_delta.x;
  } else if (t_max.y <= t_max.z) {
    c.y += dir.y;
    t_max.y += t_delta.y;
  } else {
    c.z += dir.z;
    t_max.z += t_delta.z;
  }
}

// One ray's walk over the brick grid (volume_ray.frag's main without clip code).
class RayWalk {
 public:
  RayWalk(const CastScene& s, const Sampler& smp, bool batch, const Ray& r)
      : s_(s), smp_(smp), batch_(batch), r_(r), cell_(float(s.cell[0]), float(s.cell[1]), float(s.cell[2])),
        grid_(s.grid[0], s.grid[1], s.grid[2]) {}

  vec4 run();
  /// Scalar samples read so far.
  std::int64_t samples() const { return samples_; }

 private:
  const CastScene& s_;
  const Sampler& smp_;
  bool batch_;  ///< SIMD batches (cpu_batch.h) for runs of samples
  const Ray& r_;
  vec3 cell_;
  ivec3 grid_;
  vec4 acc_{0.f};
  // Refinement's state, carried across the bricks of a run.
  float seg_b_ = 0, piece_prev_ = -1, fine_w_ = 0;
  vec4 cur_{-1.f}, ahead_{-1.f}, fine_sum_{0.f};
  vec3 fine_at_{0.f};
  int fine_ = 0;
  bool run_open_ = false;
  std::int64_t samples_ = 0;
  // refined_batch's segments ahead in this brick: their bounds, the middles read, their lit
  // colours (a refined one's from its fine samples) and whether each is refined with a fine
  // sample in the next brick (left to refined()); `next_` the first not yet composited
  // (next_ == ahead_n_: none left).
  struct Ahead {
    float sb[kMaxBatch], se[kMaxBatch];
    Colours read, lit;
    bool crosses[kMaxBatch];
  };
  Ahead batch_ahead_;
  int ahead_n_ = 0, next_ = 0;

  void blend(vec4 c) { acc_ += (1.f - acc_.a) * c; }
  /// The scalar passes' fine samples of the segment at seg_b_ begin (refined()'s mode 2).
  void start_fine() {
    fine_ = tsp::kRefineSamples;
    fine_sum_ = vec4(0.f);
    fine_at_ = vec3(0.f);
    fine_w_ = 0.f;
  }
  vec3 texel(float t, vec3 scale) const { return (r_.entry + r_.dir * t) * scale; }
  void neighbours(ivec3 c, vec4 page, bool level0, BrickView& b) const;
  // The walk's parts, as volume_ray.frag's (docs/rendering.md, "The caster in parts").
  bool run_closes(ivec3 c, vec4 page, float t_out, vec3 t_max, ivec3 dir, vec4& next_page,
                  ivec3& next_c) const;
  void textured_brick(ivec3 c, vec4 page, float t, float t_out, vec3 t_max, ivec3 dir,
                      float& t_next, float& m_cur, bool run);
  void level_brick(float t, float t_out, float& t_next, float dtm, vec3 scale, vec3 phase,
                   const BrickView& b, int tf_row);
  void segments(float t, float t_out, float& t_next, vec3 scale, const BrickView& b,
                bool closing);
  void refined(float t, float t_out, ivec3 c, const BrickView& b, bool closing,
               vec4 next_page, ivec3 next_c, float& t_next);
  int refined_batch(float t_out, const BrickView& b, bool closing,
                    const float* piece_row);
  void read_ahead(float t_out, const BrickView& b, bool closing, const float* piece_row);
  void fine_ahead(float t_out, bool closing, const BrickView& b, Positions& at);
};

}  // namespace tspgl::detail
