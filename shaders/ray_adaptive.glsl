// The one-pass caster's full-resolution textured bricks with adaptive sampling (TSP_ADAPTIVE,
// GL only): a segment starting at b takes the multiplier m of the step cell there (step_map:
// kStepCell³ voxels) and runs to the next boundary of the grid of m spacings (so equal
// multipliers keep equal segments); its TF row is corrected for m spacings. The run's segments
// are cut at its ends as in ray_segments.glsl.
uniform sampler3D step_map;          // per step cell: step multiplier, TF row coordinate
uniform vec3 step_scale;             // sample point → step_map coordinate

void sample_run(Brick br, bool closing, vec4 next_page, ivec3 next_c) {
  if (!run_open) {
    t_next = br.t;  // here t_next is where the next segment starts
    run_open = true;
  }
  float b = t_next;
  float u = (r.depth_entry + b * r.cos_theta) / spacing;  // depth in spacings
  vec3 p0 = entry + r.ray * b;
  vec3 q = p0 * step_scale;
  vec3 dq = r.ray * br.dtm * step_scale;
  vec3 tcb = (p0 * br.scale + br.page.xyz) * atlas_scale;
  while (acc.a < kOpaque && b < br.t_out - 1e-4 * br.dtm) {
    vec2 st = texture(step_map, q).rg;
    float k = (floor(u / st.x + 1e-3) + 1.0) * st.x - u;
    float room = (br.t_out - b) / br.dtm;
    if (k > room) {
      if (closing)
        k = room;
      else if (0.5 * k >= room)
        break;  // its middle is in the next brick
    }
    vec4 s = sample_row(tcb + br.dtc * (0.5 * k), br.tc_lo, br.tc_hi, st.y);
    if (k < st.x) s = cut_sample(s, k / st.x);
    acc += (1.0 - acc.a) * s;
    b += br.dtm * k;
    u += k;
    tcb += br.dtc * k;
    q += dq * k;
  }
  t_next = b;
  if (closing) run_open = false;
}
