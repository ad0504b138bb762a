// The one-pass caster's full-resolution textured bricks without probes (TSP_SEGMENTS; the CPU
// caster's RayWalk::segments): segments of the slice planes' grid [k·spacing, (k + 1)·spacing] in
// depth, each sampled at its middle — except where a run of full-resolution textured bricks
// begins (the ray's entry, or after an empty, flat or level brick) and ends: there the segment
// is cut exactly at the run's boundary, sampled at the middle of what is left, its opacity
// corrected to that length. Samples on fixed planes alone miss or add up to half a spacing at
// each end of every ray, which dominates their error at coarse spacings (docs/rendering.md). A
// segment whose middle lies past this brick is left to the next brick of the run (closing:
// the run ends in this brick). With TSP_PREINT each segment reads the pre-integrated table at
// the scalars of its two ends instead of the point lookup at its middle; a cut one reads the
// table for a whole segment and corrects its opacity to the length.

// The segment [front, back] with middle mid: the point lookup, or (TSP_PREINT) pre-integrated
// with the front end carried from the previous segment in u_prev.
vec4 segment_sample(vec3 mid, vec3 front, vec3 back, vec3 lo, vec3 hi) {
#ifdef TSP_PREINT
  return sample_segment(mid, front, back, lo, hi, u_prev);
#else
  return sample_point(mid, lo, hi);
#endif
}

void sample_run(Brick b, bool closing, vec4 next_page, ivec3 next_c) {
  vec3 tc = b.tc;
  if (!run_open) {  // the first segment, from the brick's entry to the next plane
    float d = r.depth_entry + b.t * r.cos_theta;
    float t_b = ((floor(d / spacing) + 1.0) * spacing - r.depth_entry) / r.cos_theta;
    if (closing) t_b = min(t_b, b.t_out);
    float k = (t_b - b.t) / b.dtm;
    u_prev = -1.0;
    if (k > 1e-4) {
      vec3 tcm = ((entry + r.ray * (0.5 * (b.t + t_b))) * b.scale + b.page.xyz) * atlas_scale;
      vec3 tcf = ((entry + r.ray * b.t) * b.scale + b.page.xyz) * atlas_scale;
      vec3 tcb = ((entry + r.ray * t_b) * b.scale + b.page.xyz) * atlas_scale;
      vec4 s = segment_sample(tcm, tcf, tcb, b.tc_lo, b.tc_hi);
      acc += (1.0 - acc.a) * cut_sample(s, k);
    }
    t_next = t_b + 0.5 * b.dtm;  // here t_next is the next segment's middle
    tc = ((entry + r.ray * t_next) * b.scale + b.page.xyz) * atlas_scale;
    run_open = true;
  }
  for (; acc.a < kOpaque && t_next - 0.5 * b.dtm < b.t_out; t_next += b.dtm) {
    if (t_next >= b.t_out && !closing) break;  // its middle is in the next brick
    float k = (b.t_out - t_next) / b.dtm + 0.5;  // what is left of the segment
    vec4 s;
    if (closing && k < 1.0)
      s = cut_sample(segment_sample(tc + b.dtc * (0.5 * k - 0.5), tc - 0.5 * b.dtc,
                                    tc + b.dtc * (k - 0.5), b.tc_lo, b.tc_hi), k);
    else
      s = segment_sample(tc, tc - 0.5 * b.dtc, tc + 0.5 * b.dtc, b.tc_lo, b.tc_hi);
    acc += (1.0 - acc.a) * s;
    tc += b.dtc;
  }
  if (closing) run_open = false;
}
