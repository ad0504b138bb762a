// The ray through this fragment's exit point and its span in depth (dot with the view direction),
// shared by the box programs (prepended to them). Rays run from the eye (perspective) or along
// ray_dir (orthographic); depth is measured along view_dir, like the slice planes.
uniform vec3 box_lo, box_hi;
uniform vec3 view_dir;   // normal of the slice planes, from the eye into the scene, over the
                         // central ray's cosine (unit for cubic voxels): depth along the central
                         // ray is its length
uniform vec3 ray_dir;    // unit, the orthographic rays (view_dir unless voxels are not cubes)
uniform vec3 eye;        // perspective only
uniform int perspective;
in vec3 exit_point;

struct RaySpan {
  vec3 ray;           // unit ray direction
  float cos_theta;    // dot(ray, view_dir) > 0
  float depth_entry;  // depth of the entry point (the eye when it is inside the box)
  float depth_exit;   // depth of this fragment
};

RaySpan ray_span() {
  RaySpan r;
  r.ray = perspective != 0 ? normalize(exit_point - eye) : ray_dir;
  // Walking back from the exit point, p(t) = exit − t·ray leaves the box at the first slab
  // crossing: t = min over axes of max((exit − lo)/ray, (exit − hi)/ray).
  vec3 inv = 1.0 / max(abs(r.ray), vec3(1e-12)) * sign(r.ray + vec3(1e-30));
  vec3 ta = (exit_point - box_lo) * inv, tb = (exit_point - box_hi) * inv;
  vec3 far_t = max(ta, tb);
  float t = min(min(far_t.x, far_t.y), far_t.z);
  if (perspective != 0) t = min(t, length(exit_point - eye));
  t = max(t, 0.0);
  r.cos_theta = max(dot(r.ray, view_dir), 1e-6);
  r.depth_exit = dot(exit_point, view_dir);
  r.depth_entry = r.depth_exit - t * r.cos_theta;
  return r;
}
