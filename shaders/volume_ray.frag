#version 330 core
// The whole volume ray cast in one pass (one fragment per pixel, on the volume box's exit face):
// the ray walks the brick grid front to back and does, per brick, what the page says —
//   empty:    nothing (transparent or not drawn); the ray leaps over the largest cube of empty
//             bricks centred there (empty-space skipping by a Chebyshev distance map);
//   flat:     one colour with opacity per voxel of depth, composited exactly over the ray's depth
//             through the brick, α = 1 − (1 − α₁)^L (a coherent node, class UP);
//   textured: samples on the slice planes dot(p, view_dir) = (k + ½)·spacing inside the brick,
//             read from the brick's atlas slot through the spacing-corrected premultiplied TF —
//             the samples slicing would take; with use_preintegrated, each sample reads the
//             pre-integrated segment between the half-way points to its neighbours. A page of
//             an LOD level brick (factor f = 2^l per axis, l packed in w) maps voxels to texels
//             at 1/f and samples every m·spacing, m = the largest f, on planes (k + ½)·m·spacing,
//             each sample's opacity corrected to the length of ray it stands for inside the
//             brick: α_L = 1 − (1 − α)^(L/spacing) (spec §9, §14).
// With TSP_SEGMENTS (the caster without probes), full-resolution textured bricks are sampled in
// the slice planes' segments, each at its middle, the first and last of each run of such bricks
// cut exactly where the run begins and ends; with TSP_PREINT as well, each segment reads the
// pre-integrated table at the scalars of its two ends instead of the point lookup. With TSP_ADAPTIVE as well (adaptive
// sampling), a segment spans m spacings (to the next boundary of the grid of m spacings), m
// read with its TF row from step_map for the cell (kStepCell³ voxels) where it starts.
// It stops once the ray is opaque (early ray termination). With a clip solid (clip.glsl) the
// textured samples outside the ray's kept intervals are skipped and, with clip_surface, the ray
// stops opaque where it first meets the solid's surface; the renderer draws every brick the
// surface may cross textured and flags it (only flagged bricks look at the intervals).
// (box_ray.glsl, sample_tf.glsl and clip.glsl are prepended.)
uniform float spacing;
uniform vec3 atlas_scale;            // 1 / atlas size in texels
uniform sampler3D pages;             // per brick: textured (xyz atlas offset, w = 1 + lx + 8·ly +
                                     // 64·lz + 512·clip + 1024·row, l = log2 LOD factor,
                                     // row = the level's TF row), flat (rgb,
                                     // w = ln(1 − α₁) < 0) or empty (x = radius of the cube of
                                     // empty bricks around it, w = 0)
uniform vec3 cell;                   // sample spacings one brick covers, per axis
uniform sampler2D level_tfs;         // coarse levels' TF rows (tsp/metric/level_tf.h): row r
                                     // the TF blurred by the r-th σ, corrected for spacing
uniform ivec3 grid;                  // bricks per axis
#ifdef TSP_ADAPTIVE
uniform sampler3D step_map;          // per step cell: step multiplier, TF row coordinate
uniform vec3 step_scale;             // sample point → step_map coordinate
#endif
uniform int use_surface_depth;        // 1: rays end at the surface splats' depths
uniform sampler2D surface_depth;     // per pixel, the surface's depth along view_dir
const float kOpaque = 0.999;
const float kNudge = 1e-3;
const int kClipFlag = 512;           // BrickPages::kClipFlag
const int kLevelRowUnit = 1024;      // BrickPages::kLevelRowUnit: code / it = the TF row
const float kLevelTfRows = 16.0;     // tsp::kLevelTfRows           // voxels into the volume, to pick the first brick
out vec4 colour;

// The surface of probe `probe` at sample point p seen along ray, opaque: the value at texture
// coordinate tc (clamped to the brick's [tc_lo, tc_hi]) through surface_tf, shaded by the
// probe's normal.
vec4 shaded_surface(vec3 p, vec3 ray, int probe, vec3 tc, vec3 tc_lo, vec3 tc_hi) {
  vec3 col = texture(surface_tf, texture(volume, clamp(tc, tc_lo, tc_hi)).r * surface_map.x +
                                     surface_map.y).rgb;
  vec3 n = probe_normal(probe, grid_origin + grid_spacing * p);
  return vec4(col * (0.35 + 0.65 * abs(dot(n, normalize(grid_spacing * ray)))), 1.0);
}

// The clip surface where the ray meets it (clip_intervals in clip.glsl), from this brick's
// texture at that point, composited opaque into acc.
float t_surface = kFar;  // ray parameter of the surface (kFar: none, or clipping only)
int surface_probe = -1;
int iv_k = 0;            // the kept interval the samples have reached
void draw_surface(vec3 entry, vec3 ray, vec3 scale, vec3 page_offset, vec3 tc_lo, vec3 tc_hi,
                  inout vec4 acc) {
  vec3 p = entry + ray * t_surface;
  acc += (1.0 - acc.a) * shaded_surface(p, ray, surface_probe,
                                        (p * scale + page_offset) * atlas_scale, tc_lo, tc_hi);
}

// The surface of probe `probe` at sample point p, from the page of the brick holding p (a brick
// the surface crosses is always textured).
vec4 surface_colour(vec3 p, vec3 ray, int probe) {
  ivec3 c = clamp(ivec3(floor(p / cell)), ivec3(0), grid - 1);
  vec4 page = texelFetch(pages, c, 0);
  if (page.w <= 0.5) return vec4(0.0);
  int code = (int(page.w + 0.5) - 1) & (kClipFlag - 1);
  vec3 scale = 1.0 / vec3(ivec3(1) << ivec3(code & 7, (code >> 3) & 7, (code >> 6) & 7));
  vec3 lo = vec3(c) * cell;
  return shaded_surface(p, ray, probe, (p * scale + page.xyz) * atlas_scale,
                        (lo * scale + page.xyz) * atlas_scale,
                        (min(lo + cell, box_hi) * scale + page.xyz) * atlas_scale);
}

// The kept interval the samples have reached, as scalars (the common case — one interval —
// never indexes the arrays per sample).
float cur_s = kFar, cur_e = -kFar;
// How many samples of step dt from t to the next kept one (0: t is kept; −1: none is left).
float skip_to_kept(float t, float dt) {
  while (t > cur_e && iv_k + 1 < iv_n) {
    ++iv_k;
    cur_s = iv_s[iv_k];
    cur_e = iv_e[iv_k];
  }
  if (t > cur_e) return -1.0;
  return t >= cur_s ? 0.0 : ceil((cur_s - t) / dt);
}

// Where the gradient's taps beyond brick c's faces read (g_beyond_lo/hi in sample_tf.glsl): the
// neighbour across each face when both are level-0 textures (a level brick or one beside an
// empty, flat or level brick keeps one-sided differences on that face).
void find_neighbours(ivec3 c, vec4 page, bool level0) {
  for (int a = 0; a < 3; ++a) {
    for (int side = 0; side < 2; ++side) {
      ivec3 cn = c;
      cn[a] += side == 0 ? -1 : 1;
      vec4 s = vec4(0.0);
      if (level0 && cn[a] >= 0 && cn[a] < grid[a]) {
        vec4 pn = texelFetch(pages, cn, 0);
        if (pn.w > 0.5 && ((int(pn.w + 0.5) - 1) & (kClipFlag - 1)) == 0)
          s = vec4((pn.xyz - page.xyz) * atlas_scale, 1.0);
      }
      if (side == 0)
        g_beyond_lo[a] = s;
      else
        g_beyond_hi[a] = s;
    }
  }
}

// A level brick's sample through its TF row (the TF averaged over the spread of the voxels it
// stands for): stencil and shading as sample_colour's point lookup.
vec4 sample_level(vec3 tc, vec3 lo, vec3 hi, int row) {
  if (use_stencil != 0 && texture(volume, clamp(tc, lo, hi)).g < 0.5) return vec4(0.0);
  return shade(texture(level_tfs, vec2(tf_coord(tc, lo, hi), (float(row) + 0.5) / kLevelTfRows)),
               tc, lo, hi);
}

// A sample standing for k (≤ 1) of its full segment: opacity 1 − (1 − α)^k, premultiplied.
vec4 cut_sample(vec4 s, float k) {
  if (s.a <= 0.0) return s;
  float a = 1.0 - pow(max(1.0 - s.a, 0.0), k);
  return vec4(s.rgb * (a / s.a), a);
}

#ifdef TSP_REFINE
// Refinement (tsp/frame/refine.h): row 0 of tf_refine is the point lookup with each entry's piece
// (a run of entries over which the TF is nearly straight, tsp::tf_pieces) packed into its
// opacity as α + 2·piece; row 1 the TF corrected for a step of spacing / kRefineSamples.
uniform sampler2D tf_refine;
const int kRefineSamples = 6;  // tsp::kRefineSamples
const float kPieceRow = 0.25, kFineRow = 0.75;
float piece_of(vec4 e) { return floor(e.a * 0.5); }
#endif

void main() {
  RaySpan r = ray_span();
  float len = (r.depth_exit - r.depth_entry) / r.cos_theta;
  if (len <= 0.0) discard;
  vec3 entry = exit_point - r.ray * len;
  if (use_surface_depth != 0) {
    // An opaque surface (surface_splat.frag) ends the ray where it lies: only what is in front
    // of it is composited over it (the compositor copied its picture under the volume).
    float cut = (texelFetch(surface_depth, ivec2(gl_FragCoord.xy), 0).r - r.depth_entry) /
                r.cos_theta;
    if (cut <= 0.0) discard;
    len = min(len, cut);
  }
#if TSP_CLIP == 2
  // An intersection (the common case: one plane, a box, a sphere) keeps one interval of the
  // ray: the ray is cut to it here and walks it as an unclipped ray. With the surface on, a ray
  // entering the solid through its surface shows that surface alone (nothing lies in front), and
  // one leaving through it sees it behind the volume. This variant has no other clip code:
  // llvmpipe runs every branch of a shader under a mask, so the general code would cost every
  // sample (docs/results.md).
  int back_probe = -1;  // the probe whose surface ends the ray (surface on), or −1
  {
    int ps, pe;
    vec2 kept = kept_interval(entry, r.ray, ps, pe);
    float s = max(kept.x, 0.0), e = min(kept.y, len);
    if (s >= e) discard;
    if (clip_surface != 0 && kept.x > 0.0) {
      colour = surface_colour(entry + r.ray * kept.x, r.ray, ps);
      return;
    }
    if (clip_surface != 0 && kept.y < len) back_probe = pe;
    entry += r.ray * s;
    r.depth_entry += s * r.cos_theta;
    len = e - s;
  }
#endif
  // 3-D DDA over the brick grid (Amanatides & Woo): t_max is where the ray leaves the current
  // brick through each axis' face, t_delta a whole brick's worth of t along each axis. Empty
  // bricks carry the Chebyshev radius of the empty cube around them: the ray leaps out of it.
  vec3 inv = 1.0 / max(abs(r.ray), vec3(1e-12));
  ivec3 dir = ivec3(sign(r.ray + vec3(1e-30)));
  vec3 far_side = step(0.0, r.ray);  // 1 where the ray leaves a brick through its hi face
  vec3 t_delta = cell * inv;
  float t = 0.0;
  ivec3 c = clamp(ivec3(floor((entry + r.ray * kNudge) / cell)), ivec3(0), grid - 1);
  vec3 t_max = abs((vec3(c) + far_side) * cell - entry) * inv;
  float dt = spacing / r.cos_theta;
  // t of the next slice plane k: ((k + ½)·spacing − depth_entry) / cos θ.
  float t_next = ((ceil(r.depth_entry / spacing - 0.5) + 0.5) * spacing - r.depth_entry) /
                 r.cos_theta;
  float m_cur = 1.0;  // the sample step multiplier t_next is aligned to
  vec4 acc = vec4(0.0);
  float u_prev = -1.0;  // tf coordinate half a spacing behind the previous sample (−1: none)
#ifdef TSP_REFINE
  // The caster's refinement state, carried across the bricks of a run (see its loop).
  float seg_b = 0.0, piece_prev = -1.0, fine_w = 0.0;
  vec4 cur = vec4(-1.0), ahead = vec4(-1.0), fine_sum = vec4(0.0);
  vec3 fine_at = vec3(0.0);  // opacity-weighted sum of the fine samples' points
  int fine = 0;
#endif
  bool run_open = false;  // TSP_SEGMENTS: inside a run of full-resolution textured bricks
  bool done = false;    // the ray met the clip surface
  if (clip_on()) {      // the kept intervals, and where the ray first meets the surface
    clip_intervals(entry, r.ray, len);
    if (iv_n > 0) {
      cur_s = iv_s[0];
      cur_e = iv_e[0];
    }
    for (int k = 0; clip_surface != 0 && k < iv_n; ++k) {
      if (iv_s[k] > 0.0 && iv_s[k] < len && iv_ps[k] >= 0) {
        t_surface = iv_s[k];
        surface_probe = iv_ps[k];
        break;
      }
      if (iv_e[k] > 0.0 && iv_e[k] < len && iv_pe[k] >= 0) {
        t_surface = iv_e[k];
        surface_probe = iv_pe[k];
        break;
      }
    }
  }
  int max_steps = grid.x + grid.y + grid.z + 2;
  for (int i = 0; i < max_steps; ++i) {
    vec4 page = texelFetch(pages, c, 0);
    if (page.w == 0.0) {
      // Leap to where the ray leaves the empty cube c ± radius, and find the brick there.
      vec3 face = (vec3(c) + far_side + (2.0 * far_side - 1.0) * page.x) * cell;
      vec3 tf = abs(face - entry) * inv;
      t = min(min(tf.x, tf.y), tf.z);
      if (t >= len) break;
      c = clamp(ivec3(floor((entry + r.ray * (t + kNudge)) / cell)), ivec3(0), grid - 1);
      t_max = abs((vec3(c) + far_side) * cell - entry) * inv;
      if (t_next < t) t_next += ceil((t - t_next) / (dt * m_cur)) * dt * m_cur;
      u_prev = -1.0;
      run_open = false;
      continue;
    }
    float t_out = min(min(min(t_max.x, t_max.y), t_max.z), len);
    if (page.w > 0.5) {
      int code = int(page.w + 0.5) - 1;
      // Only bricks the clip surface may cross test their samples against the solid.
      bool brick_clip = clip_on() && (code & kClipFlag) != 0;
      int tf_row = code / kLevelRowUnit;  // a level brick's TF row (0: the TF itself)
      code &= kClipFlag - 1;
      if (use_shading != 0) find_neighbours(c, page, code == 0);
      ivec3 lv = ivec3(code & 7, (code >> 3) & 7, (code >> 6) & 7);
      vec3 scale = 1.0 / vec3(ivec3(1) << lv);
      float m = float(1 << max(lv.x, max(lv.y, lv.z)));
      if (m != m_cur) {  // onto this level's planes (k + ½)·m·spacing, from where the ray is
        float sp = spacing * m;
        float d = r.depth_entry + t * r.cos_theta;
        t_next = ((ceil(d / sp - 0.5) + 0.5) * sp - r.depth_entry) / r.cos_theta;
        m_cur = m;
        u_prev = -1.0;
      }
      float dtm = dt * m;
      // Clamped to the brick's own box: its atlas neighbours never bleed in, whatever the slot.
      vec3 lo = vec3(c) * cell;
      vec3 tc_lo = (lo * scale + page.xyz) * atlas_scale;
      vec3 tc_hi = (min(lo + cell, box_hi) * scale + page.xyz) * atlas_scale;
      vec3 tc = ((entry + r.ray * t_next) * scale + page.xyz) * atlas_scale;
      vec3 dtc = r.ray * dtm * scale * atlas_scale;
      if (m == 1.0) {
        // Stretch by stretch of kept samples (one stretch, the whole brick, without a clip
        // solid): no test per sample.
        for (;;) {
          float stretch_end = t_out;
          if (brick_clip) {
            float skip = skip_to_kept(t_next, dtm);
            if (skip < 0.0) {  // nothing is kept further along the ray: it ends here
              done = true;
              break;
            }
            if (skip > 0.0) {
              t_next += skip * dtm;
              tc += dtc * skip;
              u_prev = -1.0;
            }
            stretch_end = min(t_out, min(cur_e + 1e-6 * dtm, t_surface));
          }
#if defined(TSP_SEGMENTS)
          // Segments of the slice planes' grid [k·spacing, (k + 1)·spacing] in depth, each
          // sampled at its middle — except where a run of full-resolution textured bricks begins
          // (the ray's entry, or after an empty, flat or level brick) and ends: there the
          // segment is cut exactly at the run's boundary, sampled at the middle of what is
          // left, its opacity corrected to that length. Samples on fixed planes alone miss or
          // add up to half a spacing at each end of every ray, which dominates their error at
          // coarse spacings (docs/rendering.md). A segment whose middle lies past this brick is
          // left to the next brick of the run.
          bool closing = t_out >= len;
          vec4 next_page = page;  // the next brick of the run (where it goes on)
          ivec3 next_c = c;
          if (!closing) {  // the run ends here unless the next brick is textured at level 0
            ivec3 cn = c;
            if (t_max.x <= t_max.y && t_max.x <= t_max.z)
              cn.x += dir.x;
            else if (t_max.y <= t_max.z)
              cn.y += dir.y;
            else
              cn.z += dir.z;
            closing = any(lessThan(cn, ivec3(0))) || any(greaterThanEqual(cn, grid));
            if (!closing) {
              next_page = texelFetch(pages, cn, 0);
              next_c = cn;
              float w = next_page.w;
              closing = w <= 0.5 || ((int(w + 0.5) - 1) & (kClipFlag - 1)) != 0;
            }
          }
#ifdef TSP_ADAPTIVE
          // Adaptive sampling: a segment starting at b takes the multiplier m of the cell there
          // and runs to the next boundary of the grid of m spacings (so equal multipliers keep
          // equal segments); its TF row is corrected for m spacings.
          if (!run_open) {
            t_next = t;  // here t_next is where the next segment starts
            run_open = true;
          }
          float b = t_next;
          float u = (r.depth_entry + b * r.cos_theta) / spacing;  // depth in spacings
          vec3 p0 = entry + r.ray * b;
          vec3 q = p0 * step_scale;
          vec3 dq = r.ray * dtm * step_scale;
          vec3 tcb = (p0 * scale + page.xyz) * atlas_scale;
          while (acc.a < kOpaque && b < t_out - 1e-4 * dtm) {
            vec2 st = texture(step_map, q).rg;
            float k = (floor(u / st.x + 1e-3) + 1.0) * st.x - u;
            float room = (t_out - b) / dtm;
            if (k > room) {
              if (closing)
                k = room;
              else if (0.5 * k >= room)
                break;  // its middle is in the next brick
            }
            vec4 s = sample_row(tcb + dtc * (0.5 * k), tc_lo, tc_hi, st.y);
            if (k < st.x) s = cut_sample(s, k / st.x);
            acc += (1.0 - acc.a) * s;
            b += dtm * k;
            u += k;
            tcb += dtc * k;
            q += dq * k;
          }
          t_next = b;
#elif defined(TSP_REFINE)
          // Refinement: the segments of the plain caster (cut where the run begins and ends),
          // each sampled at its middle — unless the scalar there and the one at either
          // neighbouring segment's middle fall in different pieces of the TF (a band or bend
          // lies between them): then the segment is sampled kRefineSamples times through the
          // fine TF and lit once, at the opacity-weighted mean of those samples' positions.
          // One loop, one scalar and one TF fetch per pass, whatever it samples: llvmpipe runs
          // a branch's fetches, or an inner loop, at a cost to every segment (docs/results.md).
          // Carried across the bricks of a run: the segment [seg_b, seg_e], the previous
          // middle's piece, this middle's lookup (cur; a < 0: not read), the
          // next middle's (ahead), and a refinement in progress (fine samples left, their sum).
          if (!run_open) {
            seg_b = t;
            piece_prev = -1.0;  // read at the run's entry first
            cur.a = -1.0;
            fine = 0;
            run_open = true;
          }
          for (int guard = 0; guard < 4096 && acc.a < kOpaque; ++guard) {
            float d_b = r.depth_entry + seg_b * r.cos_theta;
            float seg_e = ((floor(d_b / spacing + 1e-4) + 1.0) * spacing - r.depth_entry) /
                          r.cos_theta;
            if (closing) seg_e = min(seg_e, t_out);
            if (seg_e - seg_b < 1e-4 * dtm) {  // the run's end
              seg_b = seg_e;
              break;
            }
            float mid = 0.5 * (seg_b + seg_e);
            if (!closing && fine == 0 && mid >= t_out) break;  // the next brick's segment
            // This pass's sample: the run's entry, this middle, a fine sample, or the next
            // middle (the run's end where there is no next segment).
            int mode = piece_prev < 0.0 ? 0 : cur.a < 0.0 ? 1 : fine > 0 ? 2 : 3;
            float ts = mode == 0 ? seg_b : mode == 1 ? mid : mode == 2
                ? seg_b + (seg_e - seg_b) * (float(kRefineSamples - fine) + 0.5) / float(kRefineSamples)
                : (closing && seg_e >= t_out ? seg_e
                   : 0.5 * (seg_e + (closing ? min(seg_e + dt, t_out) : seg_e + dt)));
            if (mode != 3 && ts >= t_out && !closing) break;  // in the next brick
            // (The next middle may lie in the next brick of the run: read there. A closing
            // brick has none: its run's last read, at t_out, is on its own face.)
            bool beyond = ts >= t_out && !closing;
            vec3 off = beyond ? next_page.xyz : page.xyz;
            vec3 b_lo = beyond ? vec3(next_c) * cell : lo;
            vec3 tcs = ((entry + r.ray * ts) * scale + off) * atlas_scale;
            vec2 v = texture(volume, clamp(tcs, (b_lo * scale + off) * atlas_scale,
                                           (min(b_lo + cell, box_hi) * scale + off) *
                                               atlas_scale)).rg;
            vec4 e = texture(tf_refine, vec2(v.r * tf_map.x + tf_map.y,
                                             mode == 2 ? kFineRow : kPieceRow));
            if (use_stencil != 0 && v.g < 0.5) e = vec4(0.0, 0.0, 0.0, mode == 2 ? 0.0 : 2.0 * piece_of(e));
            float k = (seg_e - seg_b) / dt;
            vec4 c = vec4(0.0);
            vec3 at = tcs;
            bool advance = false;
            if (mode == 0) {
              piece_prev = piece_of(e);
            } else if (mode == 1) {
              cur = e;
            } else if (mode == 2) {
              if (k < 1.0) e = cut_sample(e, k);
              // Sample points, not texture coordinates: a segment's fine samples may lie in two
              // bricks of the run, whose atlas slots differ.
              fine_at += (1.0 - fine_sum.a) * e.a * (entry + r.ray * ts);
              fine_w += (1.0 - fine_sum.a) * e.a;
              fine_sum += (1.0 - fine_sum.a) * e;
              if (--fine == 0) {
                c = fine_sum;
                at = fine_w > 0.0 ? (fine_at / fine_w * scale + page.xyz) * atlas_scale : tcs;
                advance = true;
              }
            } else {
              ahead = e;
              float piece = piece_of(cur);
              if (piece != piece_prev || piece != piece_of(e)) {
                fine = kRefineSamples;
                fine_sum = vec4(0.0);
                fine_at = vec3(0.0);
                fine_w = 0.0;
              } else {
                c = vec4(cur.rgb, cur.a - 2.0 * piece);
                if (k < 1.0) c = cut_sample(c, k);
                at = ((entry + r.ray * mid) * scale + page.xyz) * atlas_scale;
                advance = true;
              }
            }
            acc += (1.0 - acc.a) * shade(c, at, tc_lo, tc_hi);
            if (advance) {
              piece_prev = piece_of(cur);
              cur = ahead;
              seg_b = seg_e;
            }
          }
          t_next = seg_b;
#else
          if (!run_open) {  // the first segment, from the brick's entry to the next plane
            float d = r.depth_entry + t * r.cos_theta;
            float t_b = ((floor(d / spacing) + 1.0) * spacing - r.depth_entry) / r.cos_theta;
            if (closing) t_b = min(t_b, t_out);
            float k = (t_b - t) / dtm;
            u_prev = -1.0;
            if (k > 1e-4) {
              vec3 tcm = ((entry + r.ray * (0.5 * (t + t_b))) * scale + page.xyz) * atlas_scale;
#ifdef TSP_PREINT
              vec3 tcf = ((entry + r.ray * t) * scale + page.xyz) * atlas_scale;
              vec3 tcb = ((entry + r.ray * t_b) * scale + page.xyz) * atlas_scale;
              vec4 s = sample_segment(tcm, tcf, tcb, tc_lo, tc_hi, u_prev);
#else
              vec4 s = sample_point(tcm, tc_lo, tc_hi);
#endif
              acc += (1.0 - acc.a) * cut_sample(s, k);
            }
            t_next = t_b + 0.5 * dtm;  // here t_next is the next segment's middle
            tc = ((entry + r.ray * t_next) * scale + page.xyz) * atlas_scale;
            run_open = true;
          }
          for (; acc.a < kOpaque && t_next - 0.5 * dtm < t_out; t_next += dtm) {
            if (t_next >= t_out && !closing) break;  // its middle is in the next brick
            float k = (t_out - t_next) / dtm + 0.5;  // what is left of the segment
            vec4 s;
#ifdef TSP_PREINT
            // Pre-integrated: the segment's colour from the scalars at its two ends (the front
            // carried from the previous segment); a cut one reads the table for a whole segment
            // and corrects its opacity to the length.
            if (closing && k < 1.0)
              s = cut_sample(sample_segment(tc + dtc * (0.5 * k - 0.5), tc - 0.5 * dtc,
                                            tc + dtc * (k - 0.5), tc_lo, tc_hi, u_prev), k);
            else
              s = sample_segment(tc, tc - 0.5 * dtc, tc + 0.5 * dtc, tc_lo, tc_hi, u_prev);
#else
            if (closing && k < 1.0)
              s = cut_sample(sample_point(tc + dtc * (0.5 * k - 0.5), tc_lo, tc_hi), k);
            else
              s = sample_point(tc, tc_lo, tc_hi);
#endif
            acc += (1.0 - acc.a) * s;
            tc += dtc;
          }
#endif
          if (closing) run_open = false;
#else
          for (; t_next < stretch_end; t_next += dtm) {
            acc += (1.0 - acc.a) * sample_colour(tc, 0.5 * dtc, tc_lo, tc_hi, u_prev);
            if (acc.a >= kOpaque) break;
            tc += dtc;
          }
#endif
          if (!brick_clip || acc.a >= kOpaque || t_next >= t_out) break;
          if (t_next >= t_surface) {  // the surface before the next sample: opaque, the end
            draw_surface(entry, r.ray, scale, page.xyz, tc_lo, tc_hi, acc);
            done = true;
            break;
          }
        }
      } else {
        run_open = false;
        // Each sample stands for its slab of the ray inside this brick: the first from where the
        // ray entered, the last to where it leaves (one sample mid-way when no plane falls
        // inside), so the lengths add up to the brick's exactly, whatever the step — no gap or
        // overlap where levels meet. Opacity corrected to the length: α_L = 1 − (1 − α)^(L/dt).
        float first = t_next;
        if (first >= t_out) {
          first = 0.5 * (t + t_out);
          tc = ((entry + r.ray * first) * scale + page.xyz) * atlas_scale;
        }
        for (float tj = first; tj < t_out; tj += dtm) {
          float lo_j = tj == first ? t : tj - 0.5 * dtm;
          float hi_j = tj + dtm >= t_out ? t_out : tj + 0.5 * dtm;
          if (brick_clip) {
            if (tj >= t_surface) {
              draw_surface(entry, r.ray, scale, page.xyz, tc_lo, tc_hi, acc);
              done = true;
              break;
            }
            if (skip_to_kept(tj, dtm) != 0.0) {  // (level bricks: sample by sample)
              u_prev = -1.0;
              tc += dtc;
              continue;
            }
          }
          vec4 s;
          if (tf_row > 0) {
            s = sample_level(tc, tc_lo, tc_hi, tf_row);
            u_prev = -1.0;  // (no pre-integrated run through a level row)
          } else {
            s = sample_colour(tc, 0.5 * dtc, tc_lo, tc_hi, u_prev);
          }
          if (s.a > 0.0) {
            float a = 1.0 - pow(max(1.0 - s.a, 0.0), (hi_j - lo_j) / dt);
            s = vec4(s.rgb * (a / s.a), a);
          }
          acc += (1.0 - acc.a) * s;
          if (acc.a >= kOpaque) break;
          tc += dtc;
        }
        if (t_next < t_out) t_next += ceil((t_out - t_next) / dtm) * dtm;
      }
      // The surface after this brick's last sample but inside it.
      if (brick_clip && !done && acc.a < kOpaque && t_surface < t_out) {
        draw_surface(entry, r.ray, scale, page.xyz, tc_lo, tc_hi, acc);
        done = true;
      }
    } else {
      float a = 1.0 - exp(page.w * (t_out - t) * r.cos_theta);
      acc += (1.0 - acc.a) * vec4(page.rgb * a, a);
      u_prev = -1.0;
      run_open = false;
      if (t_next < t_out) t_next += ceil((t_out - t_next) / (dt * m_cur)) * dt * m_cur;
    }
    if (done || acc.a >= kOpaque || t_out >= len) break;
    t = t_out;
    // Step into the neighbour across the nearest face.
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
    if (any(lessThan(c, ivec3(0))) || any(greaterThanEqual(c, grid))) break;
  }
#if TSP_CLIP == 2
  if (back_probe >= 0 && acc.a < kOpaque)
    acc += (1.0 - acc.a) * surface_colour(entry + r.ray * len, r.ray, back_probe);
#endif
  if (acc.a <= 0.0) discard;
  colour = acc;
}
