#version 330 core
// A textured brick ray cast: samples on the slice planes dot(p, view_dir) = (k + ½)·spacing that
// fall in [entry, exit) (the samples its slices would take), composited front to back with the
// same premultiplied, spacing-corrected TF lookup as slicing, stopping once the ray is opaque.
// The result is blended over what lies behind. (The shared constants, box_ray.glsl and
// sample_tf.glsl are prepended.)
uniform float spacing;
uniform vec3 tex_origin;  // −(atlas texel coordinate − sample coordinate)
uniform vec3 tex_scale;   // 1 / atlas size
uniform vec3 tex_lo, tex_hi;  // the brick's own box in texture coordinates
out vec4 colour;
void main() {
  RaySpan r = ray_span();
  float k_first = ceil(r.depth_entry / spacing - 0.5);
  float k_end = ceil(r.depth_exit / spacing - 0.5);
  int n = int(k_end - k_first);
  if (n <= 0) discard;
  float back = (r.depth_exit - (k_first + 0.5) * spacing) / r.cos_theta;
  vec3 tc = (exit_point - r.ray * back - tex_origin) * tex_scale;
  vec3 step = r.ray * (spacing / r.cos_theta) * tex_scale;
  vec4 acc = vec4(0.0);
  float u_front = -1.0;
  for (int i = 0; i < n; ++i) {
    acc += (1.0 - acc.a) * sample_colour(tc, 0.5 * step, tex_lo, tex_hi, u_front);
    if (acc.a >= kOpaque) break;
    tc += step;
  }
  if (acc.a <= 0.0) discard;
  colour = acc;
}
