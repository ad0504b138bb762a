// One textured sample's colour, shared by the textured programs (prepended to them): the scalar
// at texture coordinate tc, clamped to the brick's own box [lo, hi] so atlas neighbours never
// bleed in, through the premultiplied, spacing-corrected TF (nearest: the metrics' exact table);
// with use_preintegrated, the pre-integrated segment between the half-way points to the
// neighbouring samples instead. With use_stencil the texture's second channel holds the
// stencil (1 inside the data): a sample where its trilinear blend is below ½ lies outside the
// mesh and is never drawn. With use_shading, every sample that is not transparent is lit
// (shade(): Blinn–Phong with a headlight, the gradient by central differences).
uniform sampler3D volume;            // the brick atlas (or the baseline's whole volume)
uniform sampler1D transfer_function;
uniform sampler2D preintegrated;     // segment colour over (front, back) tf coordinates
uniform vec2 tf_map;                 // tf coordinate = normalised scalar · tf_map.x + tf_map.y
uniform int use_preintegrated;
uniform int use_stencil;
uniform int use_shading;
uniform vec4 phong;                  // ambient, diffuse, specular, specular power
uniform vec3 light_dir;              // unit, towards the viewer (the headlight), world axes
uniform vec3 inv_voxel;              // 1 / the world size of a voxel per axis

// Blinn–Phong with a headlight (light and view along the central ray, so the half vector is the
// light): c lit by the normal from the scalar's central differences one texel either side of
// tc (in the brick's box; beyond its faces from the neighbour brick in the one-pass caster, else
// one-sided), taken to world axes. Two-sided:
// |n·l|. Where the gradient vanishes (uniform data) the sample stays unlit, like a flat node.
// Specular light is white, weighted by the sample's opacity (premultiplied).
#ifdef TSP_CLIP
// The one-pass caster (TSP_CLIP is defined in every variant of it) sets, on entering a level-0
// textured brick, where a tap beyond each face reads the neighbour brick: xyz the shift from
// this brick's atlas coordinates to the neighbour's, w 1 where the neighbour holds a level-0
// texture (else 0: the tap is clamped and the difference one-sided). Per brick, not per tap:
// a branch per tap cost 1.9× a lit frame on llvmpipe, which runs both sides of a branch where
// its lanes differ (docs/results.md, issue 29).
vec4 g_beyond_lo[3] = vec4[3](vec4(0.0), vec4(0.0), vec4(0.0));
vec4 g_beyond_hi[3] = vec4[3](vec4(0.0), vec4(0.0), vec4(0.0));
#endif

// One tap of the central differences: the scalar one texel from tc along `axis` (q) and where
// along that axis it was read — q itself, or clamped onto the brick's face when the texel lies
// beyond it and no neighbour supplies it (then the difference is one-sided). No branch.
vec2 gradient_tap(vec3 q, int axis, vec3 lo, vec3 hi) {
  vec3 c = clamp(q, lo, hi);
#ifdef TSP_CLIP
  bool up = q[axis] > hi[axis];
  vec4 s = up ? g_beyond_hi[axis] : g_beyond_lo[axis];
  float use = (up || q[axis] < lo[axis]) ? s.w : 0.0;
  c[axis] = mix(c[axis], q[axis], use);
  return vec2(texture(volume, c + s.xyz * use).r, c[axis]);
#else
  return vec2(texture(volume, c).r, c[axis]);
#endif
}

vec4 shade(vec4 c, vec3 tc, vec3 lo, vec3 hi) {
  if (use_shading == 0 || c.a <= 0.0) return c;
  vec3 d = 1.0 / vec3(textureSize(volume, 0));
  vec3 g;
  for (int a = 0; a < 3; ++a) {
    vec3 e = vec3(0.0);
    e[a] = d[a];
    vec2 f = gradient_tap(tc + e, a, lo, hi), b = gradient_tap(tc - e, a, lo, hi);
    // The difference over the span between the two taps (one-sided on a face): per texel.
    g[a] = (f.x - b.x) / max(f.y - b.y, 1e-3 * d[a]) * d[a];
  }
  g *= inv_voxel;
  float len = length(g);
  float ndl = abs(dot(g, light_dir)) / max(len, 1e-30);
  vec3 lit = c.rgb * (phong.x + phong.y * ndl) + phong.z * pow(ndl, phong.w) * c.a;
  // Uniform data has no normal: there the sample keeps its colour, as flat nodes do; lighting
  // fades in up to a change of kFlatGradient of the value range per voxel.
  return vec4(mix(c.rgb, lit, smoothstep(0.0, kFlatGradient, len)), c.a);
}

float tf_coord(vec3 tc, vec3 lo, vec3 hi) {
  return texture(volume, clamp(tc, lo, hi)).r * tf_map.x + tf_map.y;
}

// half_step: half a spacing along the ray, in texture coordinates. u_front carries the front
// half-way point's tf coordinate from one sample of a run to the next (< 0: none yet).
vec4 sample_colour(vec3 tc, vec3 half_step, vec3 lo, vec3 hi, inout float u_front) {
  if (use_stencil != 0 && texture(volume, clamp(tc, lo, hi)).g < 0.5) {
    u_front = -1.0;
    return vec4(0.0);
  }
  if (use_preintegrated == 0)
    return shade(texture(transfer_function, tf_coord(tc, lo, hi)), tc, lo, hi);
  if (u_front < 0.0) u_front = tf_coord(tc - half_step, lo, hi);
  float u_back = tf_coord(tc + half_step, lo, hi);
  vec4 c = texture(preintegrated, vec2(u_front, u_back));
  u_front = u_back;
  return shade(c, tc, lo, hi);
}

// The point lookup alone (the caster's segment loop, built without pre-integration).
vec4 sample_point(vec3 tc, vec3 lo, vec3 hi) {
  if (use_stencil != 0 && texture(volume, clamp(tc, lo, hi)).g < 0.5) return vec4(0.0);
  return shade(texture(transfer_function, tf_coord(tc, lo, hi)), tc, lo, hi);
}

// The pre-integrated segment (the caster's segment loop with pre-integration) from tc_front to
// tc_back, tc its middle (stencil and shading): the table entry for the tf coordinates at its
// ends. u_front carries the front end's from the previous segment of a run (< 0: read it).
vec4 sample_segment(vec3 tc, vec3 tc_front, vec3 tc_back, vec3 lo, vec3 hi, inout float u_front) {
  if (use_stencil != 0 && texture(volume, clamp(tc, lo, hi)).g < 0.5) {
    u_front = -1.0;
    return vec4(0.0);
  }
  if (u_front < 0.0) u_front = tf_coord(tc_front, lo, hi);
  float u_back = tf_coord(tc_back, lo, hi);
  vec4 c = texture(preintegrated, vec2(u_front, u_back));
  u_front = u_back;
  return shade(c, tc, lo, hi);
}

#ifdef TSP_ADAPTIVE
// Adaptive sampling (tsp/frame/sample_steps.h): row `row` (a texture coordinate) of the table
// whose row r is the point lookup for a step of spacing·kStepMultipliers[r].
uniform sampler2D tf_rows;
vec4 sample_row(vec3 tc, vec3 lo, vec3 hi, float row) {
  if (use_stencil != 0 && texture(volume, clamp(tc, lo, hi)).g < 0.5) return vec4(0.0);
  return shade(texture(tf_rows, vec2(tf_coord(tc, lo, hi), row)), tc, lo, hi);
}
#endif
