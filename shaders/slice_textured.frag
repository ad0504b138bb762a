#version 330 core
// One slice of a textured brick: scalar (16-bit, normalised) → transfer-function lookup. The TF
// texture already holds premultiplied colours with opacity corrected for the slice spacing
// (spec §9), so a fragment is one 3D and one 1D fetch. Fully transparent samples are discarded:
// on a software rasteriser that skips their blend and store.
in vec3 texcoord;
uniform sampler3D volume;
uniform sampler1D transfer_function;
uniform vec2 tf_map;  // tf coordinate = normalised scalar · tf_map.x + tf_map.y
uniform sampler2D preintegrated;  // segment colour over (front, back) tf coordinates
uniform int use_preintegrated;
uniform vec3 back_step;  // one spacing along the view, in sample coordinates
uniform vec3 tex_scale;  // 1 / atlas size (slice.vert's)
uniform vec3 tex_lo, tex_hi;  // the brick's own box in texture coordinates (atlas neighbours never bleed in)
out vec4 colour;
void main() {
  if (use_preintegrated != 0) {
    // The segment centred on this slice: half a spacing in front of it to half behind.
    vec3 half_step = 0.5 * back_step * tex_scale;
    float u_front = texture(volume, clamp(texcoord - half_step, tex_lo, tex_hi)).r;
    float u_back = texture(volume, clamp(texcoord + half_step, tex_lo, tex_hi)).r;
    colour = texture(preintegrated, vec2(u_front, u_back) * tf_map.x + tf_map.y);
  } else {
    colour = texture(transfer_function,
                     texture(volume, clamp(texcoord, tex_lo, tex_hi)).r * tf_map.x + tf_map.y);
  }
  if (colour.a <= 0.0) discard;
}
