#version 330 core
// A coherent node (class UP) drawn once: one colour, one opacity per voxel of depth, composited
// exactly over the ray's depth extent L through the box: α = 1 − (1 − α₁)^L (premultiplied).
// This is what its slices converge to as the spacing goes to zero, at one fragment per pixel.
// (box_ray.glsl is prepended.)
uniform vec3 flat_rgb;             // the node's mean colour, not premultiplied
uniform float log_transmittance;   // ln(1 − α₁), α₁ the opacity per voxel of depth (≤ 0)
out vec4 colour;
void main() {
  RaySpan r = ray_span();
  float a = 1.0 - exp(log_transmittance * max(r.depth_exit - r.depth_entry, 0.0));
  if (a <= 0.0) discard;
  colour = vec4(flat_rgb * a, a);
}
