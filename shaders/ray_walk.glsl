// The one-pass caster's shared state and helpers (prepended to volume_ray.frag after
// box_ray.glsl, sample_tf.glsl and clip.glsl, before the sampling parts): its uniforms, the ray
// being walked (the CPU caster's RayWalk members, src/render/cpu_walk.h), the brick it is in
// (Brick), and what every variant uses — clip surfaces, the kept interval, the gradient's
// neighbour pages, a cut sample's opacity. Constants shared with C++ (kOpaque, kNudge,
// kClipFlag, kLevelRowUnit, kLevelTfRows, kRefineSamples, …) are written before every file by
// the program cache (src/render/ray_programs.cpp) from src/render/ray_constants.h.
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
uniform int use_surface_depth;        // 1: rays end at the surface splats' depths
uniform sampler2D surface_depth;     // per pixel, the surface's depth along view_dir
out vec4 colour;

// The ray (set by main before the walk): its span, entry point and length in t.
RaySpan r;
vec3 entry;
float len;
float dt;          // t per sample spacing
float t_next;      // the next sample (or segment boundary) on the slice planes' grid
float m_cur = 1.0; // the sample step multiplier t_next is aligned to
float u_prev = -1.0;  // tf coordinate half a spacing behind the previous sample (−1: none)
vec4 acc = vec4(0.0);
bool run_open = false;  // segments: inside a run of full-resolution textured bricks
bool done = false;      // the ray met the clip surface

// A textured brick as the sampling parts see it: its grid cell and page, the ray's span in it
// [t, t_out], the step dtm (= dt · its LOD factor), scale (sample coordinates → its texels),
// its box lo, its atlas box [tc_lo, tc_hi], the texture coordinate of t_next (tc) and per step
// (dtc), whether its samples are tested against the clip solid, and a level brick's TF row.
struct Brick {
  ivec3 c;
  vec4 page;
  float t, t_out, dtm;
  vec3 scale, lo, tc_lo, tc_hi, tc, dtc;
  bool clip;
  int tf_row;
};

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

// The kept intervals of the ray and where it first meets the clip surface (the general clip
// variant; clip_on() is the constant false in the others).
void begin_clip() {
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

// A sample standing for k (≤ 1) of its full segment: opacity 1 − (1 − α)^k, premultiplied.
vec4 cut_sample(vec4 s, float k) {
  if (s.a <= 0.0) return s;
  float a = 1.0 - pow(max(1.0 - s.a, 0.0), k);
  return vec4(s.rgb * (a / s.a), a);
}
