#include "render/cpu_caster.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include "render/cpu_batch.h"
#include "render/cpu_sample.h"
#include "tsp/core/parallel_for.h"
#include "tsp/frame/refine.h"
#include "tsp/metric/level_tf.h"

namespace tspgl {

namespace {

using detail::BrickView;
using detail::cut_sample;
using detail::kNudge;
using detail::kOpaque;
using detail::Sampler;
using glm::ivec3;
using glm::vec3;
using glm::vec4;

/// Pixels per side of the tiles the workers take (rays of a tile share bricks in cache).
constexpr int kTile = 16;
/// Refinement's rows: the point lookup with pieces packed into opacity, and the fine step.
constexpr int kPieceRow = 0, kFineRow = 1;

float piece_of(vec4 e) { return std::floor(e.a * 0.5f); }

// The ray through a pixel: where it leaves the box (the fragment's exit_point), and its span in
// depth (box_ray.glsl's ray_span).
struct Ray {
  vec3 dir{0};
  vec3 entry{0};
  float cos_theta = 1, depth_entry = 0, len = 0;
};

// False when the pixel's line of sight misses the box between the near and far planes (no
// fragment of the box's back faces covers its centre).
bool pixel_ray(const CastScene& s, int px, int py, Ray& r) {
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

vec4 page_at(const CastScene& s, ivec3 c) {
  const float* p =
      s.pages + 4 * (std::size_t(c.x) + std::size_t(s.grid[0]) *
                                            (std::size_t(c.y) + std::size_t(s.grid[1]) * std::size_t(c.z)));
  return {p[0], p[1], p[2], p[3]};
}

bool inside(const CastScene& s, ivec3 c) {
  return c.x >= 0 && c.y >= 0 && c.z >= 0 && c.x < s.grid[0] && c.y < s.grid[1] &&
         c.z < s.grid[2];
}

bool level0_textured(vec4 page) {
  return page.w > 0.5f && ((int(page.w + 0.5f) - 1) & (detail::kClipFlag - 1)) == 0;
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
  // colours; `next_` the first not yet composited (next_ == ahead_n_: none left).
  struct Ahead {
    float sb[detail::kMaxBatch], se[detail::kMaxBatch];
    detail::Colours read, lit;
  };
  Ahead batch_ahead_;
  int ahead_n_ = 0, next_ = 0;

  void blend(vec4 c) { acc_ += (1.f - acc_.a) * c; }
  vec3 texel(float t, vec3 scale) const { return (r_.entry + r_.dir * t) * scale; }
  void neighbours(ivec3 c, vec4 page, bool level0, BrickView& b) const;
  void segments(float t, float t_out, float& t_next, vec3 scale, vec4 page, const BrickView& b,
                bool closing);
  void refined(float t, float t_out, vec4 page, ivec3 c, const BrickView& b, bool closing,
               vec4 next_page, ivec3 next_c, float& t_next);
  int refined_batch(float t_out, vec4 page, const BrickView& b, bool closing,
                    const float* piece_row);
  bool fine_batch(float t_out, const BrickView& b, bool closing, float seg_e);
};

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
void RayWalk::segments(float t, float t_out, float& t_next, vec3 scale, vec4 page,
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

// Refinement (volume_ray.frag, TSP_REFINE): one pass per scalar read, as the shader's loop.
void RayWalk::refined(float t, float t_out, vec4 page, ivec3 c, const BrickView& b, bool closing,
                      vec4 next_page, ivec3 next_c, float& t_next) {
  const float dt = s_.spacing / r_.cos_theta;
  const int k_entries = s_.tf.entries;
  const float* rows[2] = {s_.tf.refine + 4 * k_entries * kPieceRow,
                          s_.tf.refine + 4 * k_entries * kFineRow};
  const vec3 lo = vec3(c) * cell_;
  constexpr int kSamples = tsp::kRefineSamples;
  ahead_n_ = next_ = 0;  // the segments read ahead belong to the last brick
  if (!run_open_) {
    seg_b_ = t;
    piece_prev_ = -1.f;
    cur_.a = -1.f;
    fine_ = 0;
    run_open_ = true;
  }
  for (int guard = 0; guard < 4096 && acc_.a < kOpaque; ++guard) {
    const float d_b = r_.depth_entry + seg_b_ * r_.cos_theta;
    float seg_e = ((std::floor(d_b / s_.spacing + 1e-4f) + 1.f) * s_.spacing - r_.depth_entry) /
                  r_.cos_theta;
    if (closing) seg_e = std::min(seg_e, t_out);
    if (seg_e - seg_b_ < 1e-4f * dt) {  // the run's end
      seg_b_ = seg_e;
      break;
    }
    const float mid = 0.5f * (seg_b_ + seg_e);
    if (!closing && fine_ == 0 && mid >= t_out) break;  // the next brick's segment
    const int mode = piece_prev_ < 0.f ? 0 : cur_.a < 0.f ? 1 : fine_ > 0 ? 2 : 3;
    if (mode == 3 && batch_ && refined_batch(t_out, page, b, closing, rows[0]) > 0) continue;
    const float ts =
        mode == 0 ? seg_b_
        : mode == 1 ? mid
        : mode == 2 ? seg_b_ + (seg_e - seg_b_) * (float(kSamples - fine_) + 0.5f) / float(kSamples)
                    : (closing && seg_e >= t_out
                           ? seg_e
                           : 0.5f * (seg_e + (closing ? std::min(seg_e + dt, t_out) : seg_e + dt)));
    if (mode != 3 && ts >= t_out && !closing) break;  // in the next brick
    const bool beyond = ts >= t_out;
    const vec3 k_at = beyond ? vec3(next_page) - 0.5f : b.k;
    const vec3 b_lo = beyond ? vec3(next_c) * cell_ : lo;
    const vec3 tcs = texel(ts, vec3(1.f));
    const vec3 q = glm::clamp(tcs, b_lo, glm::min(b_lo + cell_, s_.box_hi));
    const float v = smp_.tex.fetch(q, k_at);
    ++samples_;
    vec4 e = detail::entry(detail::lookup(rows[mode == 2 ? 1 : 0], k_entries, smp_.tf_coord(v)));
    if (s_.stencil && smp_.tex.fetch(q, k_at, 1) < 0.5f)
      e = vec4(0.f, 0.f, 0.f, mode == 2 ? 0.f : 2.f * piece_of(e));
    const float k = (seg_e - seg_b_) / dt;
    vec4 col(0.f);
    vec3 at = tcs;
    bool advance = false;
    if (mode == 0) {
      piece_prev_ = piece_of(e);
    } else if (mode == 1) {
      cur_ = e;
    } else if (mode == 2) {
      if (k < 1.f) e = cut_sample(e, k);
      fine_at_ += (1.f - fine_sum_.a) * e.a * tcs;  // (points: the same in every brick's u)
      fine_w_ += (1.f - fine_sum_.a) * e.a;
      fine_sum_ += (1.f - fine_sum_.a) * e;
      if (--fine_ == 0) {
        col = fine_sum_;
        at = fine_w_ > 0.f ? fine_at_ / fine_w_ : tcs;
        advance = true;
      }
    } else {
      ahead_ = e;
      const float piece = piece_of(cur_);
      if (piece != piece_prev_ || piece != piece_of(e)) {
        fine_ = kSamples;
        fine_sum_ = vec4(0.f);
        fine_at_ = vec3(0.f);
        fine_w_ = 0.f;
      } else {
        col = vec4(vec3(cur_), cur_.a - 2.f * piece);
        if (k < 1.f) col = cut_sample(col, k);
        at = texel(mid, vec3(1.f));
        advance = true;
      }
    }
    if (col.a > 0.f) blend(smp_.shade(col, at, b));
    if (advance) {
      piece_prev_ = piece_of(cur_);
      cur_ = ahead_;
      seg_b_ = seg_e;
    }
  }
  t_next = seg_b_;
}

// Refinement's passes that read the next middle (mode 3) for as many segments ahead as a batch
// holds, in SIMD: the middles' lookups at once, then the segments' lit colours at once, then
// the passes replayed in order as refined() would make them — up to the first segment that is
// refined (left in its state: the fine samples follow in refined()), the ray's opacity, or a
// middle in the next brick. Returns the passes made (0: none, refined() makes this one).
int RayWalk::refined_batch(float t_out, vec4 page, const BrickView& b, bool closing,
                           const float* piece_row) {
  Ahead& a = batch_ahead_;
  if (next_ >= ahead_n_ || a.sb[next_] != seg_b_) {  // read the segments ahead
    const float dt = s_.spacing / r_.cos_theta;
    detail::Positions reads, mids;
    int n = 0;
    for (float sb = seg_b_; n < detail::kMaxBatch; ++n) {
      const float d_b = r_.depth_entry + sb * r_.cos_theta;
      float se = ((std::floor(d_b / s_.spacing + 1e-4f) + 1.f) * s_.spacing - r_.depth_entry) /
                 r_.cos_theta;
      if (closing) se = std::min(se, t_out);
      if (se - sb < 1e-4f * dt) break;  // the run's end
      const float mid = 0.5f * (sb + se);
      if (!closing && mid >= t_out) break;  // the next brick's segment
      const float ts = closing && se >= t_out
                           ? se
                           : 0.5f * (se + (closing ? std::min(se + dt, t_out) : se + dt));
      if (ts >= t_out) break;  // read in the next brick: refined() does it
      const vec3 r = texel(ts, vec3(1.f)), m = texel(mid, vec3(1.f));
      reads.x[n] = r.x;
      reads.y[n] = r.y;
      reads.z[n] = r.z;
      mids.x[n] = m.x;
      mids.y[n] = m.y;
      mids.z[n] = m.z;
      a.sb[n] = sb;
      a.se[n] = se;
      sb = se;
    }
    ahead_n_ = n;
    next_ = 0;
    if (n == 0) return 0;
    detail::sample_batch(smp_, b, piece_row, reads, n, false, a.read);
    samples_ += n;
    for (int j = 0; j < n; ++j) {  // segment j composites the middle read before it
      const vec4 cur =
          j == 0 ? cur_ : vec4(a.read.r[j - 1], a.read.g[j - 1], a.read.b[j - 1], a.read.a[j - 1]);
      vec4 col(vec3(cur), cur.a - 2.f * piece_of(cur));
      const float k = (a.se[j] - a.sb[j]) / dt;
      if (k < 1.f) col = cut_sample(col, k);
      a.lit.r[j] = col.r;
      a.lit.g[j] = col.g;
      a.lit.b[j] = col.b;
      a.lit.a[j] = col.a;
    }
    if (s_.shade) detail::shade_batch(smp_, b, mids, n, a.lit);
  }
  int made = 0;
  for (; next_ < ahead_n_ && acc_.a < kOpaque; ++made, ++next_) {
    const int j = next_;
    const vec4 e(a.read.r[j], a.read.g[j], a.read.b[j], a.read.a[j]);
    const float piece = piece_of(cur_);
    if (piece != piece_prev_ || piece != piece_of(e)) {  // refine this segment
      seg_b_ = a.sb[j];
      ahead_ = e;
      if (!fine_batch(t_out, b, closing, a.se[j])) {  // (a fine sample in the next brick)
        ++next_;  // after its fine samples, segment j + 1 goes on from the batch
        fine_ = tsp::kRefineSamples;
        fine_sum_ = vec4(0.f);
        fine_at_ = vec3(0.f);
        fine_w_ = 0.f;
        return made + 1;
      }
      continue;
    }
    const vec4 col(a.lit.r[j], a.lit.g[j], a.lit.b[j], a.lit.a[j]);
    if (col.a > 0.f) blend(col);
    piece_prev_ = piece;
    cur_ = e;
    seg_b_ = a.se[j];
  }
  return made;
}

// A refined segment [seg_b_, seg_e]'s kRefineSamples fine samples in one SIMD batch, composited
// and lit as refined()'s fine passes composite them, then the segment closed (cur_ becomes
// ahead_). False, with nothing done, when a fine sample lies in the next brick of the run.
bool RayWalk::fine_batch(float t_out, const BrickView& b, bool closing, float seg_e) {
  constexpr int kSamples = tsp::kRefineSamples;
  const float dt = s_.spacing / r_.cos_theta;
  detail::Positions pos;
  float ts = seg_b_;
  for (int i = 0; i < kSamples; ++i) {
    ts = seg_b_ + (seg_e - seg_b_) * (float(i) + 0.5f) / float(kSamples);
    if (ts >= t_out && !closing) return false;
    const vec3 u = texel(ts, vec3(1.f));
    pos.x[i] = u.x;
    pos.y[i] = u.y;
    pos.z[i] = u.z;
  }
  detail::Colours fine;
  detail::sample_batch(smp_, b, s_.tf.refine + 4 * s_.tf.entries * kFineRow, pos, kSamples, false,
                       fine);
  samples_ += kSamples;
  const float k = (seg_e - seg_b_) / dt;
  vec4 sum(0.f);
  vec3 at_sum(0.f);
  float w = 0.f;
  for (int i = 0; i < kSamples; ++i) {
    vec4 e(fine.r[i], fine.g[i], fine.b[i], fine.a[i]);
    if (k < 1.f) e = cut_sample(e, k);
    const vec3 u(pos.x[i], pos.y[i], pos.z[i]);
    at_sum += (1.f - sum.a) * e.a * u;
    w += (1.f - sum.a) * e.a;
    sum += (1.f - sum.a) * e;
  }
  const vec3 at = w > 0.f ? at_sum / w : vec3(pos.x[kSamples - 1], pos.y[kSamples - 1], pos.z[kSamples - 1]);
  if (sum.a > 0.f) blend(smp_.shade(sum, at, b));
  piece_prev_ = piece_of(cur_);
  cur_ = ahead_;
  seg_b_ = seg_e;
  return true;
}

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
  const bool refine = s_.tf.refine != nullptr;
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
    const float t_out = std::min({t_max.x, t_max.y, t_max.z, len});
    if (page.w > 0.5f) {
      int code = int(page.w + 0.5f) - 1;
      const int tf_row = code / detail::kLevelRowUnit;
      code &= detail::kClipFlag - 1;
      const ivec3 lv(code & 7, (code >> 3) & 7, (code >> 6) & 7);
      const vec3 scale(1.f / float(1 << lv.x), 1.f / float(1 << lv.y), 1.f / float(1 << lv.z));
      const float m = float(1 << std::max({lv.x, lv.y, lv.z}));
      BrickView b;
      const vec3 lo = vec3(c) * cell_;
      // The slot's offset less the texel centres' ½: whole texels (k) and, for a level brick
      // whose samples sit between its voxels, the lattice's phase (the same in every slot).
      const vec3 shift = vec3(page) - 0.5f;
      b.k = glm::floor(shift);
      const vec3 phase = shift - b.k;
      b.lo = lo * scale + phase;
      b.hi = glm::min(lo + cell_, s_.box_hi) * scale + phase;
      if (s_.shade) neighbours(c, page, code == 0, b);
      if (m != m_cur) {  // onto this level's planes (k + ½)·m·spacing
        const float sp = s_.spacing * m;
        const float d = r_.depth_entry + t * r_.cos_theta;
        t_next = ((std::ceil(d / sp - 0.5f) + 0.5f) * sp - r_.depth_entry) / r_.cos_theta;
        m_cur = m;
      }
      const float dtm = dt * m;
      if (m == 1.f) {
        // Does the run of full-resolution textured bricks go on past this one?
        bool closing = t_out >= len;
        vec4 next_page = page;
        ivec3 next_c = c;
        if (!closing) {
          ivec3 cn = c;
          if (t_max.x <= t_max.y && t_max.x <= t_max.z)
            cn.x += dir.x;
          else if (t_max.y <= t_max.z)
            cn.y += dir.y;
          else
            cn.z += dir.z;
          closing = !inside(s_, cn);
          if (!closing) {
            next_page = page_at(s_, cn);
            next_c = cn;
            closing = !level0_textured(next_page);
          }
        }
        if (refine)
          refined(t, t_out, page, c, b, closing, next_page, next_c, t_next);
        else
          segments(t, t_out, t_next, scale, page, b, closing);
        if (closing) run_open_ = false;
      } else {
        // A level brick: each sample stands for its slab of the ray inside the brick.
        run_open_ = false;
        const float* row =
            tf_row > 0 ? s_.tf.levels + 4 * std::size_t(s_.tf.entries) * std::size_t(tf_row)
                       : s_.tf.point;
        float first = t_next;
        if (first >= t_out) first = 0.5f * (t + t_out);
        vec3 tc = texel(first, scale) + phase;
        const vec3 dtc = ray * dtm * scale;
        for (float tj = first; tj < t_out; tj += dtm) {
          const float lo_j = tj == first ? t : tj - 0.5f * dtm;
          const float hi_j = tj + dtm >= t_out ? t_out : tj + 0.5f * dtm;
          vec4 smp = smp_.point(tc, b, row);
          ++samples_;
          if (smp.a > 0.f) {
            const float a = 1.f - std::pow(std::max(1.f - smp.a, 0.f), (hi_j - lo_j) / dt);
            smp = vec4(vec3(smp) * (a / smp.a), a);
          }
          blend(smp);
          if (acc_.a >= kOpaque) break;
          tc += dtc;
        }
        if (t_next < t_out) t_next += std::ceil((t_out - t_next) / dtm) * dtm;
      }
    } else {  // flat: the exact exponential over the ray's depth through the brick
      const float a = 1.f - std::exp(page.w * (t_out - t) * r_.cos_theta);
      blend(vec4(vec3(page) * a, a));
      run_open_ = false;
      if (t_next < t_out) t_next += std::ceil((t_out - t_next) / (dt * m_cur)) * dt * m_cur;
    }
    if (acc_.a >= kOpaque || t_out >= len) break;
    t = t_out;
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
    if (!inside(s_, c)) break;
  }
  return acc_;
}

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
  const Sampler sampler(scene);
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
