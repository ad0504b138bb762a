#version 330 core
// One slice of a textured brick: scalar (16-bit, normalised) → transfer function (1D lookup,
// linear between entry centres) → opacity corrected for the slice spacing (spec §9) →
// premultiplied colour for back-to-front blending with (ONE, ONE_MINUS_SRC_ALPHA).
in vec3 texcoord;
uniform sampler3D volume;
uniform sampler1D transfer_function;
uniform vec2 tf_map;           // tf coordinate = normalised scalar · tf_map.x + tf_map.y
uniform float spacing_ratio;   // Δ / Δ0 (slice spacing in voxels)
out vec4 colour;
void main() {
  float s = texture(volume, texcoord).r;
  vec4 c = texture(transfer_function, s * tf_map.x + tf_map.y);
  float a = 1.0 - pow(1.0 - clamp(c.a, 0.0, 1.0), spacing_ratio);
  colour = vec4(c.rgb * a, a);
}
