#version 330 core
// One uniform colour for every fragment.
uniform vec4 u_color;
out vec4 frag_color;

void main() {
  frag_color = u_color;
}
