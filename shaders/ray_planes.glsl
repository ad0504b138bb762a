// The one-pass caster's full-resolution textured bricks with clip probes (TSP_CLIP 1 and 2):
// point samples on the slice planes (k + ½)·spacing, stretch by stretch of kept samples (one
// stretch, the whole brick, without a clip solid: no test per sample); the ray ends opaque at
// the clip surface. The other variants sample in segments (ray_segments.glsl, ray_adaptive.glsl,
// ray_refine.glsl); this one has no CPU counterpart (the CPU caster draws no probes).
void sample_run(Brick b, bool closing, vec4 next_page, ivec3 next_c) {
  vec3 tc = b.tc;
  for (;;) {
    float stretch_end = b.t_out;
    if (b.clip) {
      float skip = skip_to_kept(t_next, b.dtm);
      if (skip < 0.0) {  // nothing is kept further along the ray: it ends here
        done = true;
        break;
      }
      if (skip > 0.0) {
        t_next += skip * b.dtm;
        tc += b.dtc * skip;
        u_prev = -1.0;
      }
      stretch_end = min(b.t_out, min(cur_e + 1e-6 * b.dtm, t_surface));
    }
    for (; t_next < stretch_end; t_next += b.dtm) {
      acc += (1.0 - acc.a) * sample_colour(tc, 0.5 * b.dtc, b.tc_lo, b.tc_hi, u_prev);
      if (acc.a >= kOpaque) break;
      tc += b.dtc;
    }
    if (!b.clip || acc.a >= kOpaque || t_next >= b.t_out) break;
    if (t_next >= t_surface) {  // the surface before the next sample: opaque, the end
      draw_surface(entry, r.ray, b.scale, b.page.xyz, b.tc_lo, b.tc_hi, acc);
      done = true;
      break;
    }
  }
}
