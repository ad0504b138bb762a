#version 330 core
// One slice of a textured brick: scalar (16-bit, normalised) → transfer-function lookup. The TF
// texture already holds premultiplied colours with opacity corrected for the slice spacing
// (spec §9), so a fragment is one 3D and one 1D fetch. Fully transparent samples are discarded:
// on a software rasteriser that skips their blend and store. (sample_tf.glsl is prepended.)
in vec3 texcoord;
uniform vec3 back_step;  // one spacing along the view, in sample coordinates
uniform vec3 tex_scale;  // 1 / atlas size (slice.vert's)
uniform vec3 tex_lo, tex_hi;  // the brick's own box in texture coordinates
out vec4 colour;
void main() {
  float u_front = -1.0;  // with pre-integration: the segment from half a spacing in front of
                         // this slice to half behind
  colour = sample_colour(texcoord, 0.5 * back_step * tex_scale, tex_lo, tex_hi, u_front);
  if (colour.a <= 0.0) discard;
}
