// One textured sample's colour, shared by the textured programs (prepended to them): the scalar
// at texture coordinate tc, clamped to the brick's own box [lo, hi] so atlas neighbours never
// bleed in, through the premultiplied, spacing-corrected TF (nearest: the metrics' exact table);
// with use_preintegrated, the pre-integrated segment between the half-way points to the
// neighbouring samples instead. With use_stencil the texture's second channel holds the
// stencil (1 inside the data): a sample where its trilinear blend is below ½ lies outside the
// mesh and is never drawn.
uniform sampler3D volume;            // the brick atlas (or the baseline's whole volume)
uniform sampler1D transfer_function;
uniform sampler2D preintegrated;     // segment colour over (front, back) tf coordinates
uniform vec2 tf_map;                 // tf coordinate = normalised scalar · tf_map.x + tf_map.y
uniform int use_preintegrated;
uniform int use_stencil;

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
  if (use_preintegrated == 0) return texture(transfer_function, tf_coord(tc, lo, hi));
  if (u_front < 0.0) u_front = tf_coord(tc - half_step, lo, hi);
  float u_back = tf_coord(tc + half_step, lo, hi);
  vec4 c = texture(preintegrated, vec2(u_front, u_back));
  u_front = u_back;
  return c;
}

// The point lookup alone (the caster's segment loop, built without pre-integration).
vec4 sample_point(vec3 tc, vec3 lo, vec3 hi) {
  if (use_stencil != 0 && texture(volume, clamp(tc, lo, hi)).g < 0.5) return vec4(0.0);
  return texture(transfer_function, tf_coord(tc, lo, hi));
}

#ifdef TSP_ADAPTIVE
// Adaptive sampling (tsp/frame/sample_steps.h): row `row` (a texture coordinate) of the table
// whose row r is the point lookup for a step of spacing·kStepMultipliers[r].
uniform sampler2D tf_rows;
vec4 sample_row(vec3 tc, vec3 lo, vec3 hi, float row) {
  if (use_stencil != 0 && texture(volume, clamp(tc, lo, hi)).g < 0.5) return vec4(0.0);
  return texture(tf_rows, vec2(tf_coord(tc, lo, hi), row));
}
#endif
