#version 330 core
// One slice of a coherent node (class UP): its mean colour, already premultiplied and corrected
// for the slice spacing on the CPU.
uniform vec4 flat_colour;
out vec4 colour;
void main() { colour = flat_colour; }
