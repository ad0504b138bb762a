// One textured sample's colour, shared by the textured programs (prepended to them): the scalar
// at texture coordinate tc, clamped to the brick's own box [lo, hi] so atlas neighbours never
// bleed in, through the premultiplied, spacing-corrected TF (nearest: the metrics' exact table);
// with use_preintegrated, the pre-integrated segment between the half-way points to the
// neighbouring samples instead.
uniform sampler3D volume;            // the brick atlas (or the baseline's whole volume)
uniform sampler1D transfer_function;
uniform sampler2D preintegrated;     // segment colour over (front, back) tf coordinates
uniform vec2 tf_map;                 // tf coordinate = normalised scalar · tf_map.x + tf_map.y
uniform int use_preintegrated;

float tf_coord(vec3 tc, vec3 lo, vec3 hi) {
  return texture(volume, clamp(tc, lo, hi)).r * tf_map.x + tf_map.y;
}

// half_step: half a spacing along the ray, in texture coordinates. u_front carries the front
// half-way point's tf coordinate from one sample of a run to the next (< 0: none yet).
vec4 sample_colour(vec3 tc, vec3 half_step, vec3 lo, vec3 hi, inout float u_front) {
  if (use_preintegrated == 0) return texture(transfer_function, tf_coord(tc, lo, hi));
  if (u_front < 0.0) u_front = tf_coord(tc - half_step, lo, hi);
  float u_back = tf_coord(tc + half_step, lo, hi);
  vec4 c = texture(preintegrated, vec2(u_front, u_back));
  u_front = u_back;
  return c;
}
