#version 330 core
// One slice of a textured brick: scalar (16-bit, normalised) → transfer-function lookup. The TF
// texture already holds premultiplied colours with opacity corrected for the slice spacing
// (spec §9), so a fragment is one 3D and one 1D fetch. Fully transparent samples are discarded:
// on a software rasteriser that skips their blend and store.
in vec3 texcoord;
uniform sampler3D volume;
uniform sampler1D transfer_function;
uniform vec2 tf_map;  // tf coordinate = normalised scalar · tf_map.x + tf_map.y
out vec4 colour;
void main() {
  float s = texture(volume, texcoord).r;
  colour = texture(transfer_function, s * tf_map.x + tf_map.y);
  if (colour.a <= 0.0) discard;
}
