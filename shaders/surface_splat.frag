#version 330 core
// A splat's disc, opaque: the field's colour through the surface TF, lit like the volume
// (Blinn–Phong with a headlight, two-sided, the splat's normal taken to world axes); its depth
// along the view (the ray caster's measure) to the second target, where the caster stops.
in vec2 disc;
in vec3 splat_normal;
in float value;
in float depth;
uniform sampler1D splat_tf;  // colours, not premultiplied
uniform vec2 splat_map;      // tf coordinate = value · x + y
uniform int use_shading;
uniform vec4 phong;          // ambient, diffuse, specular, specular power
uniform vec3 light_dir;      // unit, towards the viewer, world axes
uniform vec3 inv_voxel;      // 1 / the world size of a voxel per axis
layout(location = 0) out vec4 colour;
layout(location = 1) out float out_depth;
void main() {
  if (dot(disc, disc) > 1.0) discard;
  vec3 c = texture(splat_tf, value * splat_map.x + splat_map.y).rgb;
  if (use_shading != 0) {
    float ndl = abs(dot(normalize(splat_normal * inv_voxel), light_dir));
    c = c * (phong.x + phong.y * ndl) + phong.z * pow(ndl, phong.w);
  }
  colour = vec4(c, 1.0);
  out_depth = depth;
}
