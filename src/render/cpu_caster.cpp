#include "render/cpu_caster.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include "render/cpu_refine.h"
#include "render/cpu_walk.h"
#include "tsp/core/parallel_for.h"
#include "tsp/frame/refine.h"
#include "tsp/metric/level_tf.h"

namespace tspgl {

namespace detail {

void RayWalk::neighbours(ivec3 c, vec4 page, bool level0, BrickView& b) const {
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side) {
      ivec3 cn = c;
      cn[a] += side == 0 ? -1 : 1;
      vec4 sh(0.f);
      if (level0 && inside(s_, cn)) {
        const vec4 pn = page_at(s_, cn);
        if (level0_textured(pn)) sh = vec4(vec3(pn) - vec3(page), 1.f);
      }
      (side == 0 ? b.beyond_lo : b.beyond_hi)[std::size_t(a)] = sh;
    }
}

// The plain segment caster: the run's first segment cut at its entry, then each segment at its
// middle, the run's last cut where it ends.
void RayWalk::segments(float t, float t_out, float& t_next, vec3 scale,
                       const BrickView& b, bool closing) {
  const float dt = s_.spacing / r_.cos_theta;
  const float* row = s_.tf.point;
  if (!run_open_) {
    const float d = r_.depth_entry + t * r_.cos_theta;
    float t_b = ((std::floor(d / s_.spacing) + 1.f) * s_.spacing - r_.depth_entry) / r_.cos_theta;
    if (closing) t_b = std::min(t_b, t_out);
    const float k = (t_b - t) / dt;
    if (k > 1e-4f) {
      blend(cut_sample(smp_.point(texel(0.5f * (t + t_b), scale), b, row), k));
      ++samples_;
    }
    t_next = t_b + 0.5f * dt;
    run_open_ = true;
  }
  vec3 tc = texel(t_next, scale);
  const vec3 dtc = r_.dir * dt * scale;
  if (batch_) {
    // The whole segments, in SIMD batches: their samples at once, composited in order (the
    // batch past an opaque sample is dropped). The cut last segment is left to the loop below.
    detail::Positions pos;
    detail::Colours col;
    while (acc_.a < kOpaque) {
      int n = 0;
      float tj = t_next;
      vec3 p = tc;
      for (; n < detail::kMaxBatch; ++n, tj += dt, p += dtc) {
        if (!(tj - 0.5f * dt < t_out) || (tj >= t_out && !closing)) break;
        if (closing && (t_out - tj) / dt + 0.5f < 1.f) break;
        pos.x[n] = p.x;
        pos.y[n] = p.y;
        pos.z[n] = p.z;
      }
      if (n == 0) break;
      detail::sample_batch(smp_, b, row, pos, n, true, col);
      samples_ += n;
      int used = 0;
      for (; used < n && acc_.a < kOpaque; ++used, t_next += dt, tc += dtc)
        blend(vec4(col.r[used], col.g[used], col.b[used], col.a[used]));
      if (used < n) return;
    }
  }
  for (; acc_.a < kOpaque && t_next - 0.5f * dt < t_out; t_next += dt) {
    if (t_next >= t_out && !closing) break;  // its middle is in the next brick
    const float k = (t_out - t_next) / dt + 0.5f;
    if (closing && k < 1.f)
      blend(cut_sample(smp_.point(tc + dtc * (0.5f * k - 0.5f), b, row), k));
    else
      blend(smp_.point(tc, b, row));
    ++samples_;
    tc += dtc;
  }
}

bool RayWalk::run_closes(ivec3 c, vec4 page, float t_out, vec3 t_max, ivec3 dir,
                         vec4& next_page, ivec3& next_c) const {
  bool closing = t_out >= r_.len;
  next_page = page;
  next_c = c;
  if (!closing) {
    ivec3 cn = c;
    vec3 tm = t_max;
    step(cn, tm, dir, vec3(0.f));
    closing = !inside(s_, cn);
    if (!closing) {
      next_page = page_at(s_, cn);
      next_c = cn;
      closing = !level0_textured(next_page);
    }
  }
  return closing;
}

// A level brick (ray_levels.glsl): each sample stands for its slab of the ray inside the brick.
void RayWalk::level_brick(float t, float t_out, float& t_next, float dtm, vec3 scale,
                          vec3 phase, const BrickView& b, int tf_row) {
  run_open_ = false;
  const float dt = s_.spacing / r_.cos_theta;
  const float* row = tf_row > 0
                         ? s_.tf.levels + 4 * std::size_t(s_.tf.entries) * std::size_t(tf_row)
                         : s_.tf.point;
  float first = t_next;
  if (first >= t_out) first = 0.5f * (t + t_out);
  vec3 tc = texel(first, scale) + phase;
  const vec3 dtc = r_.dir * dtm * scale;
  float tj = first;
  // The share of a segment slab tj stands for: from the brick's entry (the first) or half a step
  // before, to its exit (the last) or half a step after.
  auto share = [&](float tj) {
    const float lo_j = tj == first ? t : tj - 0.5f * dtm;
    const float hi_j = tj + dtm >= t_out ? t_out : tj + 0.5f * dtm;
    return (hi_j - lo_j) / dt;
  };
  if (batch_) {  // the slabs in SIMD batches: their lit lookups at once, composited in order
    Positions pos;
    Colours col;
    alignas(64) float k[kMaxBatch];
    while (tj < t_out && acc_.a < kOpaque) {
      int n = 0;
      for (; n < kMaxBatch && tj < t_out; ++n, tj += dtm, tc += dtc) {
        k[n] = share(tj);
        pos.x[n] = tc.x;
        pos.y[n] = tc.y;
        pos.z[n] = tc.z;
      }
      sample_batch(smp_, b, row, pos, n, true, col);
      cut_batch(k, n, col);
      for (int j = 0; j < n && acc_.a < kOpaque; ++j) {
        ++samples_;
        blend(vec4(col.r[j], col.g[j], col.b[j], col.a[j]));
      }
    }
  } else {
    for (; tj < t_out; tj += dtm) {
      ++samples_;
      blend(cut_sample(smp_.point(tc, b, row), share(tj)));
      if (acc_.a >= kOpaque) break;
      tc += dtc;
    }
  }
  if (t_next < t_out) t_next += std::ceil((t_out - t_next) / dtm) * dtm;
}

// A textured brick (volume_ray.frag's textured_brick): onto its level's planes, its texels' box,
// then its samples — the run's segments (plain or refined) or a level brick's slabs.
void RayWalk::textured_brick(ivec3 c, vec4 page, float t, float t_out, vec3 t_max, ivec3 dir,
                             float& t_next, float& m_cur, bool run) {
  int code = int(page.w + 0.5f) - 1;
  const int tf_row = code / kLevelRowUnit;
  code &= kClipFlag - 1;
  const ivec3 lv(code & 7, (code >> 3) & 7, (code >> 6) & 7);
  const vec3 scale(1.f / float(1 << lv.x), 1.f / float(1 << lv.y), 1.f / float(1 << lv.z));
  const float m = float(1 << std::max({lv.x, lv.y, lv.z}));
  BrickView b;
  const vec3 lo = vec3(c) * cell_;
  // The slot's offset less the texel centres' ½: whole texels (k) and, for a level brick whose
  // samples sit between its voxels, the lattice's phase (the same in every slot).
  const vec3 shift = vec3(page) - 0.5f;
  b.k = glm::floor(shift);
  const vec3 phase = shift - b.k;
  b.lo = lo * scale + phase;
  b.hi = glm::min(lo + cell_, s_.box_hi) * scale + phase;
  if (run) {  // a run of full-resolution bricks in the dense region, ending in brick c
    b.lo = vec3(0.f);
    b.hi = s_.box_hi;
    b.run = true;
  } else if (s_.shade) {
    neighbours(c, page, code == 0, b);
  }
  if (m != m_cur) {  // onto this level's planes (k + ½)·m·spacing
    const float sp = s_.spacing * m;
    const float d = r_.depth_entry + t * r_.cos_theta;
    t_next = ((std::ceil(d / sp - 0.5f) + 0.5f) * sp - r_.depth_entry) / r_.cos_theta;
    m_cur = m;
  }
  if (m != 1.f) {
    level_brick(t, t_out, t_next, s_.spacing / r_.cos_theta * m, scale, phase, b, tf_row);
    return;
  }
  vec4 next_page;
  ivec3 next_c;
  const bool closing = run_closes(c, page, t_out, t_max, dir, next_page, next_c);
  if (s_.tf.refine != nullptr)
    refined(t, t_out, c, b, closing, next_page, next_c, t_next);
  else
    segments(t, t_out, t_next, scale, b, closing);
  if (closing) run_open_ = false;
}

// The walk (volume_ray.frag's main without clip code): a 3-D DDA over the brick grid that leaps
// over cubes of empty bricks, composites flat bricks exactly and samples textured ones.
vec4 RayWalk::run() {
  const vec3 ray = r_.dir;
  const vec3 inv = 1.f / glm::max(glm::abs(ray), vec3(1e-12f));
  const ivec3 dir(ray.x + 1e-30f >= 0 ? 1 : -1, ray.y + 1e-30f >= 0 ? 1 : -1,
                  ray.z + 1e-30f >= 0 ? 1 : -1);
  const vec3 far_side(ray.x >= 0 ? 1.f : 0.f, ray.y >= 0 ? 1.f : 0.f, ray.z >= 0 ? 1.f : 0.f);
  const vec3 t_delta = cell_ * inv;
  const float len = r_.len;
  float t = 0;
  ivec3 c = glm::clamp(ivec3(glm::floor((r_.entry + ray * kNudge) / cell_)), ivec3(0), grid_ - 1);
  vec3 t_max = glm::abs((vec3(c) + far_side) * cell_ - r_.entry) * inv;
  const float dt = s_.spacing / r_.cos_theta;
  float t_next = ((std::ceil(r_.depth_entry / s_.spacing - 0.5f) + 0.5f) * s_.spacing -
                  r_.depth_entry) / r_.cos_theta;
  float m_cur = 1;
  const int max_steps = grid_.x + grid_.y + grid_.z + 2;
  for (int i = 0; i < max_steps; ++i) {
    const vec4 page = page_at(s_, c);
    if (page.w == 0.f) {  // leap out of the cube of empty bricks around c
      const vec3 face = (vec3(c) + far_side + (2.f * far_side - 1.f) * page.x) * cell_;
      const vec3 tf = glm::abs(face - r_.entry) * inv;
      t = std::min({tf.x, tf.y, tf.z});
      if (t >= len) break;
      c = glm::clamp(ivec3(glm::floor((r_.entry + ray * (t + kNudge)) / cell_)), ivec3(0),
                     grid_ - 1);
      t_max = glm::abs((vec3(c) + far_side) * cell_ - r_.entry) * inv;
      if (t_next < t) t_next += std::ceil((t - t_next) / (dt * m_cur)) * dt * m_cur;
      run_open_ = false;
      continue;
    }
    float t_out = std::min({t_max.x, t_max.y, t_max.z, len});
    if (page.w > 0.5f && s_.runs && level0_textured(page)) {
      // The run of full-resolution bricks from c on, walked as one volume (the dense region).
      while (t_out < len) {
        ivec3 cn = c;
        vec3 tm = t_max;
        step(cn, tm, dir, t_delta);
        if (!inside(s_, cn) || !level0_textured(page_at(s_, cn))) break;
        c = cn;
        t_max = tm;
        t_out = std::min({t_max.x, t_max.y, t_max.z, len});
      }
      textured_brick(c, page_at(s_, c), t, t_out, t_max, dir, t_next, m_cur, true);
    } else if (page.w > 0.5f) {
      textured_brick(c, page, t, t_out, t_max, dir, t_next, m_cur, false);
    } else {  // flat: the exact exponential over the ray's depth through the brick
      const float a = 1.f - std::exp(page.w * (t_out - t) * r_.cos_theta);
      blend(vec4(vec3(page) * a, a));
      run_open_ = false;
      if (t_next < t_out) t_next += std::ceil((t_out - t_next) / (dt * m_cur)) * dt * m_cur;
    }
    if (acc_.a >= kOpaque || t_out >= len) break;
    t = t_out;
    step(c, t_max, dir, t_delta);
    if (!inside(s_, c)) break;
  }
  return acc_;
}

}  // namespace detail

namespace {

using namespace detail;  // the walk's own file

// Per brick: kRunSelf when it is a full-resolution page (in the dense region), and a run_bit
// for each face neighbour that is one too.
std::vector<std::int32_t> run_masks(const CastScene& s) {
  const ivec3 g(s.grid[0], s.grid[1], s.grid[2]);
  std::vector<std::int32_t> m(std::size_t(g.x) * std::size_t(g.y) * std::size_t(g.z), 0);
  auto textured = [&](ivec3 c) { return inside(s, c) && level0_textured(page_at(s, c)); };
  std::size_t i = 0;
  for (int z = 0; z < g.z; ++z)
    for (int y = 0; y < g.y; ++y)
      for (int x = 0; x < g.x; ++x, ++i) {
        const ivec3 c(x, y, z);
        if (!textured(c)) continue;
        std::int32_t bits = kRunSelf;
        for (int a = 0; a < 3; ++a)
          for (int side = 0; side < 2; ++side) {
            ivec3 n = c;
            n[a] += side == 0 ? -1 : 1;
            if (textured(n)) bits |= run_bit(a, side);
          }
        m[i] = bits;
      }
  return m;
}

/// Pixels per side of the tiles the workers take (rays of a tile share bricks in cache).
constexpr int kTile = 16;

// One tile's rays into rgba; returns the pixels drawn. Compiled twice, for x86-64-v3 (AVX2,
// FMA, BMI: what every x86 CPU of the last decade has) and for the baseline, and picked at run
// time: the caster is scalar code whose gain is FMA and SSE4.1's rounding, and `flatten`
// inlines the whole walk into each clone.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
[[gnu::target_clones("arch=x86-64-v3", "default"), gnu::flatten]]
#endif
CastStats cast_tile(const CastScene& scene, const Sampler& sampler, bool batch, int tx0, int ty0,
                    int tx1, int ty1, float* rgba) {
  CastStats n;
  for (int py = ty0; py < ty1; ++py)
    for (int px = tx0; px < tx1; ++px) {
      float* out = rgba + (std::size_t(py) * std::size_t(scene.width) + std::size_t(px)) * 4;
      Ray r;
      vec4 acc(0.f);
      if (pixel_ray(scene, px, py, r)) {
        RayWalk walk(scene, sampler, batch, r);
        acc = walk.run();
        n.samples += walk.samples();
      }
      if (acc.a <= 0.f)
        acc = vec4(0.f);
      else
        ++n.pixels;
      out[0] = acc.r;
      out[1] = acc.g;
      out[2] = acc.b;
      out[3] = acc.a;
    }
  return n;
}

}  // namespace

CastStats cast_rays(const CastScene& scene, const CastRect& rect, int threads,
                    std::vector<float>& rgba) {
  rgba.resize(std::size_t(scene.width) * std::size_t(scene.height) * 4);
  const int x0 = std::max(rect.x0, 0), y0 = std::max(rect.y0, 0);
  const int x1 = std::min(rect.x1, scene.width), y1 = std::min(rect.y1, scene.height);
  if (x1 <= x0 || y1 <= y0) return {};
  const int tiles_x = (x1 - x0 + kTile - 1) / kTile, tiles_y = (y1 - y0 + kTile - 1) / kTile;
  Sampler sampler(scene);
  if (scene.runs) sampler.runs = run_masks(scene);
  const bool batch = !scene.stencil && detail::batch_ready(sampler);
  std::atomic<std::int64_t> pixels{0}, samples{0};
  tsp::parallel_for(std::int64_t(tiles_x) * tiles_y, 1, threads,
                    [&](int, std::int64_t begin, std::int64_t end) {
    CastStats n;
    for (std::int64_t tile = begin; tile < end; ++tile) {
      const int tx = x0 + int(tile % tiles_x) * kTile, ty = y0 + int(tile / tiles_x) * kTile;
      const CastStats t = cast_tile(scene, sampler, batch, tx, ty, std::min(tx + kTile, x1),
                                    std::min(ty + kTile, y1), rgba.data());
      n.pixels += t.pixels;
      n.samples += t.samples;
    }
    pixels += n.pixels;
    samples += n.samples;
  });
  return {pixels.load(), samples.load()};
}

}  // namespace tspgl
