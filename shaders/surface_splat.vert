#version 330 core
// TetSplat's splats (tsp/surface/splat_tree.h), one instance each: an inner node as a disc of
// its radius in its plane around its centre (sample coordinates), drawn as a quad of two
// triangles whose fragments outside the disc are discarded (surface_splat.frag); a leaf as its
// own boundary triangle (the quad's second triangle degenerate).
layout(location = 0) in vec3 centre;
layout(location = 1) in vec3 normal;        // unit, in sample coordinates
layout(location = 2) in vec3 radius_value_leaf;  // radius (sample units), value, 1 for a leaf
layout(location = 3) in vec3 corner0;       // a leaf's triangle
layout(location = 4) in vec3 corner1;
layout(location = 5) in vec3 corner2;
uniform mat4 view_projection;
uniform vec3 view_dir;  // as the ray caster's (box_ray.glsl): depth = dot(point, view_dir)
out vec2 disc;          // where on the unit disc (0 on a leaf's triangle)
out vec3 splat_normal;
out float value;
out float depth;
const vec2 kCorners[6] = vec2[6](vec2(-1.0, -1.0), vec2(1.0, -1.0), vec2(1.0, 1.0),
                                 vec2(-1.0, -1.0), vec2(1.0, 1.0), vec2(-1.0, 1.0));
void main() {
  vec3 n = normalize(normal);
  vec3 p;
  if (radius_value_leaf.z > 0.5) {
    p = gl_VertexID == 0 ? corner0 : gl_VertexID == 1 ? corner1 : corner2;
    disc = vec2(0.0);
  } else {
    vec2 c = kCorners[gl_VertexID];
    vec3 u = normalize(cross(n, abs(n.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0)));
    vec3 v = cross(n, u);
    p = centre + radius_value_leaf.x * (c.x * u + c.y * v);
    disc = c;
  }
  splat_normal = n;
  value = radius_value_leaf.y;
  depth = dot(p, view_dir);
  gl_Position = view_projection * vec4(p, 1.0);
}
