// The one-pass caster's level bricks (an LOD cut's coarse bricks, every variant; the CPU caster's
// RayWalk::level_brick): each sample stands for its slab of the ray inside the brick — the first
// from where the ray entered, the last to where it leaves (one sample mid-way when no plane falls
// inside) — so the lengths add up to the brick's exactly, whatever the step: no gap or overlap
// where levels meet. Opacity corrected to the length: α_L = 1 − (1 − α)^(L/dt).

// A level brick's sample through its TF row (the TF averaged over the spread of the voxels it
// stands for): stencil and shading as sample_colour's point lookup.
vec4 sample_level(vec3 tc, vec3 lo, vec3 hi, int row) {
  if (use_stencil != 0 && texture(volume, clamp(tc, lo, hi)).g < 0.5) return vec4(0.0);
  return shade(texture(level_tfs, vec2(tf_coord(tc, lo, hi), (float(row) + 0.5) / kLevelTfRows)),
               tc, lo, hi);
}

void level_brick(Brick b) {
  run_open = false;
  vec3 tc = b.tc;
  float first = t_next;
  if (first >= b.t_out) {
    first = 0.5 * (b.t + b.t_out);
    tc = ((entry + r.ray * first) * b.scale + b.page.xyz) * atlas_scale;
  }
  for (float tj = first; tj < b.t_out; tj += b.dtm) {
    float lo_j = tj == first ? b.t : tj - 0.5 * b.dtm;
    float hi_j = tj + b.dtm >= b.t_out ? b.t_out : tj + 0.5 * b.dtm;
    if (b.clip) {
      if (tj >= t_surface) {
        draw_surface(entry, r.ray, b.scale, b.page.xyz, b.tc_lo, b.tc_hi, acc);
        done = true;
        break;
      }
      if (skip_to_kept(tj, b.dtm) != 0.0) {  // (level bricks: sample by sample)
        u_prev = -1.0;
        tc += b.dtc;
        continue;
      }
    }
    vec4 s;
    if (b.tf_row > 0) {
      s = sample_level(tc, b.tc_lo, b.tc_hi, b.tf_row);
      u_prev = -1.0;  // (no pre-integrated run through a level row)
    } else {
      s = sample_colour(tc, 0.5 * b.dtc, b.tc_lo, b.tc_hi, u_prev);
    }
    acc += (1.0 - acc.a) * cut_sample(s, (hi_j - lo_j) / dt);
    if (acc.a >= kOpaque) break;
    tc += b.dtc;
  }
  if (t_next < b.t_out) t_next += ceil((b.t_out - t_next) / b.dtm) * b.dtm;
}
