#version 330 core
// The whole volume ray cast in one pass (one fragment per pixel, on the volume box's exit face):
// the ray walks the brick grid front to back and does, per brick, what the page says —
//   empty:    nothing (transparent or not drawn); the ray leaps over the largest cube of empty
//             bricks centred there (empty-space skipping by a Chebyshev distance map);
//   flat:     one colour with opacity per voxel of depth, composited exactly over the ray's depth
//             through the brick, α = 1 − (1 − α₁)^L (a coherent node, class UP);
//   textured: samples on the slice planes dot(p, view_dir) = (k + ½)·spacing inside the brick,
//             read from the brick's atlas slot through the spacing-corrected premultiplied TF —
//             the samples slicing would take. A page of an LOD level brick (factor f = 2^l per
//             axis, l packed in w) maps voxels to texels at 1/f and samples every m·spacing,
//             m = the largest f, on planes (k + ½)·m·spacing (ray_levels.glsl, spec §9, §14).
// It stops once the ray is opaque (early ray termination). This file is the walk (the CPU
// caster's RayWalk::run, src/render/cpu_caster.cpp); how a full-resolution textured brick is
// sampled is one function, sample_run, in one part per variant (src/render/ray_programs.h):
//   ray_segments.glsl  segments cut exactly at each run's ends (and TSP_PREINT: pre-integrated)
//   ray_adaptive.glsl  segments of m spacings from a step map (TSP_ADAPTIVE)
//   ray_refine.glsl    segments refined where the TF bends between them (TSP_REFINE)
//   ray_planes.glsl    plane samples tested against the clip solid (TSP_CLIP 1, 2)
// With a clip solid (clip.glsl) the textured samples outside the ray's kept intervals are
// skipped and, with clip_surface, the ray stops opaque where it first meets the solid's surface;
// the renderer draws every brick the surface may cross textured and flags it (only flagged
// bricks look at the intervals). The program cache prepends, in order: the variant's #defines,
// the constants shared with C++, box_ray.glsl, sample_tf.glsl, clip.glsl, ray_walk.glsl,
// ray_levels.glsl and the variant's part.

// Does the run of full-resolution textured bricks end in brick c (the ray leaves the volume, or
// the next brick, across the nearest face, is not a level-0 texture)? When it goes on,
// next_page and next_c are that brick's.
bool run_closes(ivec3 c, vec4 page, float t_out, vec3 t_max, ivec3 dir, out vec4 next_page,
                out ivec3 next_c) {
  bool closing = t_out >= len;
  next_page = page;
  next_c = c;
  if (!closing) {
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
  return closing;
}

// A textured brick c over [t, t_out]: onto its level's planes, its atlas box, then its samples
// (sample_run for a full-resolution brick, level_brick for an LOD level's), then the clip
// surface if the ray meets it after the brick's last sample but inside it.
void textured_brick(ivec3 c, vec4 page, float t, float t_out, vec3 t_max, ivec3 dir) {
  int code = int(page.w + 0.5) - 1;
  Brick b;
  b.c = c;
  b.page = page;
  b.t = t;
  b.t_out = t_out;
  // Only bricks the clip surface may cross test their samples against the solid.
  b.clip = clip_on() && (code & kClipFlag) != 0;
  b.tf_row = code / kLevelRowUnit;  // a level brick's TF row (0: the TF itself)
  code &= kClipFlag - 1;
  if (use_shading != 0) find_neighbours(c, page, code == 0);
  ivec3 lv = ivec3(code & 7, (code >> 3) & 7, (code >> 6) & 7);
  b.scale = 1.0 / vec3(ivec3(1) << lv);
  float m = float(1 << max(lv.x, max(lv.y, lv.z)));
  if (m != m_cur) {  // onto this level's planes (k + ½)·m·spacing, from where the ray is
    float sp = spacing * m;
    float d = r.depth_entry + t * r.cos_theta;
    t_next = ((ceil(d / sp - 0.5) + 0.5) * sp - r.depth_entry) / r.cos_theta;
    m_cur = m;
    u_prev = -1.0;
  }
  b.dtm = dt * m;
  // Clamped to the brick's own box: its atlas neighbours never bleed in, whatever the slot.
  b.lo = vec3(c) * cell;
  b.tc_lo = (b.lo * b.scale + page.xyz) * atlas_scale;
  b.tc_hi = (min(b.lo + cell, box_hi) * b.scale + page.xyz) * atlas_scale;
  b.tc = ((entry + r.ray * t_next) * b.scale + page.xyz) * atlas_scale;
  b.dtc = r.ray * b.dtm * b.scale * atlas_scale;
  if (m == 1.0) {
    vec4 next_page;
    ivec3 next_c;
    bool closing = run_closes(c, page, t_out, t_max, dir, next_page, next_c);
    sample_run(b, closing, next_page, next_c);
  } else {
    level_brick(b);
  }
  // The surface after this brick's last sample but inside it.
  if (b.clip && !done && acc.a < kOpaque && t_surface < t_out) {
    draw_surface(entry, r.ray, b.scale, page.xyz, b.tc_lo, b.tc_hi, acc);
    done = true;
  }
}

void main() {
  r = ray_span();
  len = (r.depth_exit - r.depth_entry) / r.cos_theta;
  if (len <= 0.0) discard;
  entry = exit_point - r.ray * len;
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
  dt = spacing / r.cos_theta;
  // t of the next slice plane k: ((k + ½)·spacing − depth_entry) / cos θ.
  t_next = ((ceil(r.depth_entry / spacing - 0.5) + 0.5) * spacing - r.depth_entry) /
           r.cos_theta;
  if (clip_on()) begin_clip();  // the kept intervals, and where the ray first meets the surface
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
      textured_brick(c, page, t, t_out, t_max, dir);
    } else {  // flat: the exact exponential over the ray's depth through the brick
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
