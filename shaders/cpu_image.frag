#version 330 core
// The CPU ray caster's premultiplied picture (render/cpu_pass.h), one texel per target pixel,
// composited "over" as the GL caster's fragments are; a pixel whose ray drew nothing is
// discarded, as the GL caster discards it (the fragment count stays comparable).
uniform sampler2D image;
out vec4 colour;
void main() {
  vec4 c = texelFetch(image, ivec2(gl_FragCoord.xy), 0);
  if (c.a <= 0.0) discard;
  colour = c;
}
