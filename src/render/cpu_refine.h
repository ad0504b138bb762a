// Refinement's passes of the CPU caster's walk (volume_ray.frag's TSP_REFINE loop), in their
// own file: the scalar loop and the SIMD look-ahead of the segments ahead (their middles, the
// refined ones' fine samples and every segment's lighting in batches). Internal: included by
// cpu_caster.cpp only, so the walk's clones (cast_tile) inline it.
#pragma once
#include "render/cpu_walk.h"
#include "tsp/frame/refine.h"

namespace tspgl::detail {

// Refinement (volume_ray.frag, TSP_REFINE): one pass per scalar read, as the shader's loop.
inline void RayWalk::refined(float t, float t_out, ivec3 c, const BrickView& b, bool closing,
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
    if (mode == 3 && batch_ && refined_batch(t_out, b, closing, rows[0]) > 0) continue;
    const float ts =
        mode == 0 ? seg_b_
        : mode == 1 ? mid
        : mode == 2 ? seg_b_ + (seg_e - seg_b_) * (float(kSamples - fine_) + 0.5f) / float(kSamples)
                    : (closing && seg_e >= t_out
                           ? seg_e
                           : 0.5f * (seg_e + (closing ? std::min(seg_e + dt, t_out) : seg_e + dt)));
    if (mode != 3 && ts >= t_out && !closing) break;  // in the next brick
    // (In the next brick of the run; a closing brick has none: the run's last read, at t_out,
    // is on its own face. Reading "beyond" there took the next page's offset, an empty or flat
    // page's, and read whatever sat at that place in the atlas: pictures that changed with the
    // frames drawn before.)
    const bool beyond = ts >= t_out && !closing;
    const vec3 k_at = beyond ? vec3(next_page) - 0.5f : b.k;
    const vec3 b_lo = beyond ? vec3(next_c) * cell_ : lo;
    const vec3 tcs = texel(ts, vec3(1.f));
    const vec3 q = beyond ? glm::clamp(tcs, b_lo, glm::min(b_lo + cell_, s_.box_hi))
                          : glm::clamp(tcs, b.lo, b.hi);  // (b.lo is lo, or a run's box)
    const float v = smp_.tex.fetch(q, k_at);
    ++samples_;
    vec4 e = entry(lookup(rows[mode == 2 ? 1 : 0], k_entries, smp_.tf_coord(v)));
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
        start_fine();
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
// holds, in SIMD (read_ahead: the middles' lookups, the refined segments' fine samples and every
// segment's lit colour, each at once), then the passes replayed in order as refined() would make
// them — up to a refined segment with a fine sample in the next brick (left in its state: the
// fine samples follow in refined()), the ray's opacity, or a middle in the next brick. Returns
// the passes made (0: none, refined() makes this one).
inline int RayWalk::refined_batch(float t_out, const BrickView& b, bool closing,
                                  const float* piece_row) {
  Ahead& a = batch_ahead_;
  if (next_ >= ahead_n_ || a.sb[next_] != seg_b_) {
    read_ahead(t_out, b, closing, piece_row);
    if (ahead_n_ == 0) return 0;
  }
  int made = 0;
  for (; next_ < ahead_n_ && acc_.a < kOpaque; ++made, ++next_) {
    const int j = next_;
    const vec4 e(a.read.r[j], a.read.g[j], a.read.b[j], a.read.a[j]);
    if (a.crosses[j]) {  // refined, a fine sample in the next brick: refined() samples it
      seg_b_ = a.sb[j];
      ahead_ = e;
      ++next_;  // after its fine samples, segment j + 1 goes on from the batch
      start_fine();
      return made + 1;
    }
    const vec4 col(a.lit.r[j], a.lit.g[j], a.lit.b[j], a.lit.a[j]);
    if (col.a > 0.f) blend(col);
    piece_prev_ = piece_of(cur_);
    cur_ = e;
    seg_b_ = a.se[j];
  }
  return made;
}

// The segments ahead of seg_b_ in this brick: their bounds, their middles read (one SIMD batch)
// and their colours, cut and lit — an unrefined segment's from the middle read before it, lit at
// its middle; a refined one's from its fine samples (fine_ahead).
inline void RayWalk::read_ahead(float t_out, const BrickView& b, bool closing,
                                const float* piece_row) {
  Ahead& a = batch_ahead_;
  const float dt = s_.spacing / r_.cos_theta;
  Positions reads, at;
  int n = 0;
  // The segments end on the planes of depth (plane · spacing): the first plane past seg_b_
  // as refined() finds it, then one plane a segment, each end from its plane alone (no
  // chain of divisions and floors from one segment to the next).
  const float inv_cos = 1.f / r_.cos_theta;
  float plane = std::floor((r_.depth_entry + seg_b_ * r_.cos_theta) / s_.spacing + 1e-4f) + 1.f;
  for (float sb = seg_b_; n < kMaxBatch; ++n, plane += 1.f) {
    float se = (plane * s_.spacing - r_.depth_entry) * inv_cos;
    if (closing) se = std::min(se, t_out);
    if (se - sb < 1e-4f * dt) break;  // the run's end
    const float mid = 0.5f * (sb + se);
    if (!closing && mid >= t_out) break;  // the next brick's segment
    const float ts = closing && se >= t_out
                         ? se
                         : 0.5f * (se + (closing ? std::min(se + dt, t_out) : se + dt));
    // Read in the next brick: refined() does it. (A closing run's last read, on its far face,
    // is clamped into its box as refined() clamps it: it stays in the batch.)
    if (ts >= t_out && !closing) break;
    const vec3 r = texel(ts, vec3(1.f)), m = texel(mid, vec3(1.f));
    reads.x[n] = r.x;
    reads.y[n] = r.y;
    reads.z[n] = r.z;
    at.x[n] = m.x;
    at.y[n] = m.y;
    at.z[n] = m.z;
    a.sb[n] = sb;
    a.se[n] = se;
    sb = se;
  }
  ahead_n_ = n;
  next_ = 0;
  if (n == 0) return;
  sample_batch(smp_, b, piece_row, reads, n, false, a.read);
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
  fine_ahead(t_out, closing, b, at);
  if (s_.shade) shade_batch(smp_, b, at, n, a.lit);
}

// The refined segments among those read ahead (the pieces of the middles either side differ, as
// refined() decides in turn): their kRefineSamples fine samples each, in SIMD batches, composited
// as refined()'s fine passes composite them into the segment's colour, lit at their
// opacity-weighted position (its place in `at`). A refined segment with a fine sample in the
// next brick is marked `crosses` and left to refined().
inline void RayWalk::fine_ahead(float t_out, bool closing, const BrickView& b, Positions& at) {
  constexpr int kSamples = tsp::kRefineSamples;
  static_assert(kSamples <= kMaxBatch, "a refined segment's fine samples fit one batch");
  Ahead& a = batch_ahead_;
  const float dt = s_.spacing / r_.cos_theta;
  const int n = ahead_n_;
  int refined[kMaxBatch];
  int m = 0;
  Positions pos[kSamples];  // the refined segments' fine samples, kMaxBatch a batch
  float prev = piece_prev_;
  vec4 cur = cur_;
  for (int j = 0; j < n; ++j) {
    const vec4 e(a.read.r[j], a.read.g[j], a.read.b[j], a.read.a[j]);
    const float piece = piece_of(cur);
    a.crosses[j] = false;
    if (piece != prev || piece != piece_of(e)) {
      const float sb = a.sb[j], se = a.se[j];
      for (int i = 0; i < kSamples; ++i) {
        const float ts = sb + (se - sb) * (float(i) + 0.5f) / float(kSamples);
        a.crosses[j] = a.crosses[j] || (ts >= t_out && !closing);
        const vec3 u = texel(ts, vec3(1.f));
        const int at_i = m * kSamples + i;
        Positions& p = pos[at_i / kMaxBatch];
        p.x[at_i % kMaxBatch] = u.x;
        p.y[at_i % kMaxBatch] = u.y;
        p.z[at_i % kMaxBatch] = u.z;
      }
      if (!a.crosses[j]) refined[m++] = j;
    }
    prev = piece;
    cur = e;
  }
  if (m == 0) return;
  Colours fine[kSamples];
  const float* row = s_.tf.refine + 4 * s_.tf.entries * kFineRow;
  const int total = m * kSamples;
  for (int c = 0; c * kMaxBatch < total; ++c)
    sample_batch(smp_, b, row, pos[c], std::min(kMaxBatch, total - c * kMaxBatch), false,
                 fine[c]);
  samples_ += total;
  for (int r = 0; r < m; ++r) {
    const int j = refined[r];
    const float k = (a.se[j] - a.sb[j]) / dt;
    vec4 sum(0.f);
    vec3 at_sum(0.f), u(0.f);
    float w = 0.f;
    for (int i = 0; i < kSamples; ++i) {
      const int c = (r * kSamples + i) / kMaxBatch, l = (r * kSamples + i) % kMaxBatch;
      vec4 e(fine[c].r[l], fine[c].g[l], fine[c].b[l], fine[c].a[l]);
      if (k < 1.f) e = cut_sample(e, k);
      u = vec3(pos[c].x[l], pos[c].y[l], pos[c].z[l]);
      at_sum += (1.f - sum.a) * e.a * u;
      w += (1.f - sum.a) * e.a;
      sum += (1.f - sum.a) * e;
    }
    const vec3 lit_at = w > 0.f ? at_sum / w : u;
    a.lit.r[j] = sum.r;
    a.lit.g[j] = sum.g;
    a.lit.b[j] = sum.b;
    a.lit.a[j] = sum.a;
    at.x[j] = lit_at.x;
    at.y[j] = lit_at.y;
    at.z[j] = lit_at.z;
  }
}

}  // namespace tspgl::detail
