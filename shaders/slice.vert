#version 330 core
// Slice polygons in sample coordinates. For textured bricks, tex_origin/tex_scale map a sample
// position to the atlas texture's [0,1]³ so that the brick's sample i lands on its slot's texel
// centre.
layout(location = 0) in vec3 position;
uniform mat4 view_projection;
uniform vec3 tex_origin;  // −(atlas texel coordinate − sample coordinate)
uniform vec3 tex_scale;   // 1 / atlas size
out vec3 texcoord;
void main() {
  texcoord = (position - tex_origin) * tex_scale;
  gl_Position = view_projection * vec4(position, 1.0);
}
