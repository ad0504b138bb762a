#version 330 core
// A box drawn as its 12 triangles: the unit cube's corners mapped onto [box_lo, box_hi] in sample
// coordinates. The compositor culls front faces, so each pixel gets one fragment per box, on its
// exit face; the fragment shaders find the entry point from the ray.
layout(location = 0) in vec3 corner;  // in {0, 1}³
uniform mat4 view_projection;
uniform vec3 box_lo, box_hi;
out vec3 exit_point;
void main() {
  exit_point = mix(box_lo, box_hi, corner);
  gl_Position = view_projection * vec4(exit_point, 1.0);
}
