#version 330 core
// A textured brick ray cast: samples on the slice planes dot(p, view_dir) = (k + ½)·spacing that
// fall in [entry, exit) (the samples its slices would take), composited front to back with the
// same premultiplied, spacing-corrected TF lookup as slicing, stopping once the ray is opaque.
// The result is blended over what lies behind. (box_ray.glsl is prepended.)
uniform float spacing;
uniform sampler3D volume;
uniform sampler1D transfer_function;
uniform vec2 tf_map;
uniform sampler2D preintegrated;  // segment colour over (front, back) tf coordinates
uniform int use_preintegrated;      // tf coordinate = normalised scalar · tf_map.x + tf_map.y
uniform vec3 tex_origin;  // −(atlas texel coordinate − sample coordinate)
uniform vec3 tex_scale;   // 1 / atlas size
uniform vec3 tex_lo, tex_hi;  // the brick's own box in texture coordinates
const float kOpaque = 0.999;
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
  float u_prev = -1.0;
  for (int i = 0; i < n; ++i) {
    vec4 c;
    if (use_preintegrated != 0) {  // the segment between the half-way points to the neighbours
      if (u_prev < 0.0)
        u_prev = texture(volume, clamp(tc - 0.5 * step, tex_lo, tex_hi)).r * tf_map.x + tf_map.y;
      float u_back = texture(volume, clamp(tc + 0.5 * step, tex_lo, tex_hi)).r * tf_map.x + tf_map.y;
      c = texture(preintegrated, vec2(u_prev, u_back));
      u_prev = u_back;
    } else {
      c = texture(transfer_function, texture(volume, clamp(tc, tex_lo, tex_hi)).r * tf_map.x + tf_map.y);
    }
    acc += (1.0 - acc.a) * c;
    if (acc.a >= kOpaque) break;
    tc += step;
  }
  if (acc.a <= 0.0) discard;
  colour = acc;
}
