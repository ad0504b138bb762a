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
// It stops once the ray is opaque (early ray termination). (box_ray.glsl and sample_tf.glsl are
// prepended.)
uniform float spacing;
uniform vec3 atlas_scale;            // 1 / atlas size in texels
uniform sampler3D pages;             // per brick: textured (xyz atlas offset, w = 1 + lx + 8·ly +
                                     // 64·lz, l = log2 LOD factor), flat (rgb,
                                     // w = ln(1 − α₁) < 0) or empty (x = radius of the cube of
                                     // empty bricks around it, w = 0)
uniform vec3 cell;                   // sample spacings one brick covers, per axis
uniform ivec3 grid;                  // bricks per axis
const float kOpaque = 0.999;
const float kNudge = 1e-3;           // voxels into the volume, to pick the first brick
out vec4 colour;

void main() {
  RaySpan r = ray_span();
  float len = (r.depth_exit - r.depth_entry) / r.cos_theta;
  if (len <= 0.0) discard;
  vec3 entry = exit_point - r.ray * len;
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
      continue;
    }
    float t_out = min(min(min(t_max.x, t_max.y), t_max.z), len);
    if (page.w > 0.5) {
      int code = int(page.w + 0.5) - 1;
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
        for (; t_next < t_out; t_next += dtm) {
          acc += (1.0 - acc.a) * sample_colour(tc, 0.5 * dtc, tc_lo, tc_hi, u_prev);
          if (acc.a >= kOpaque) break;
          tc += dtc;
        }
      } else {
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
          vec4 s = sample_colour(tc, 0.5 * dtc, tc_lo, tc_hi, u_prev);
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
    } else {
      float a = 1.0 - exp(page.w * (t_out - t) * r.cos_theta);
      acc += (1.0 - acc.a) * vec4(page.rgb * a, a);
      u_prev = -1.0;
      if (t_next < t_out) t_next += ceil((t_out - t_next) / (dt * m_cur)) * dt * m_cur;
    }
    if (acc.a >= kOpaque || t_out >= len) break;
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
  if (acc.a <= 0.0) discard;
  colour = acc;
}
