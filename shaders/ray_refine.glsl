// The one-pass caster's full-resolution textured bricks with refinement (TSP_REFINE; the CPU
// caster's RayWalk::refined, src/render/cpu_refine.h; tsp/frame/refine.h): the segments of
// ray_segments.glsl (cut where the run begins and ends), each sampled at its middle — unless the
// scalar there and the one at either neighbouring segment's middle fall in different pieces of
// the TF (a band or bend lies between them): then the segment is sampled kRefineSamples times
// through the fine TF and lit once, at the opacity-weighted mean of those samples' positions.
// One loop, one scalar and one TF fetch per pass, whatever it samples: llvmpipe runs a
// branch's fetches, or an inner loop, at a cost to every segment (docs/results.md).
// Row 0 of tf_refine is the point lookup with each entry's piece (a run of entries over which
// the TF is nearly straight, tsp::tf_pieces) packed into its opacity as α + 2·piece; row 1 the
// TF corrected for a step of spacing / kRefineSamples.
uniform sampler2D tf_refine;
const float kPieceRow = 0.25, kFineRow = 0.75;
float piece_of(vec4 e) { return floor(e.a * 0.5); }

// Carried across the bricks of a run: the segment [seg_b, seg_e], the previous middle's piece,
// this middle's lookup (cur; a < 0: not read), the next middle's (ahead), and a refinement in
// progress (fine samples left, their sum, the opacity-weighted sum of their points).
float seg_b = 0.0, piece_prev = -1.0, fine_w = 0.0;
vec4 cur = vec4(-1.0), ahead = vec4(-1.0), fine_sum = vec4(0.0);
vec3 fine_at = vec3(0.0);
int fine = 0;

void sample_run(Brick b, bool closing, vec4 next_page, ivec3 next_c) {
  if (!run_open) {
    seg_b = b.t;
    piece_prev = -1.0;  // read at the run's entry first
    cur.a = -1.0;
    fine = 0;
    run_open = true;
  }
  for (int guard = 0; guard < 4096 && acc.a < kOpaque; ++guard) {
    float d_b = r.depth_entry + seg_b * r.cos_theta;
    float seg_e = ((floor(d_b / spacing + 1e-4) + 1.0) * spacing - r.depth_entry) /
                  r.cos_theta;
    if (closing) seg_e = min(seg_e, b.t_out);
    if (seg_e - seg_b < 1e-4 * b.dtm) {  // the run's end
      seg_b = seg_e;
      break;
    }
    float mid = 0.5 * (seg_b + seg_e);
    if (!closing && fine == 0 && mid >= b.t_out) break;  // the next brick's segment
    // This pass's sample: the run's entry, this middle, a fine sample, or the next middle (the
    // run's end where there is no next segment).
    int mode = piece_prev < 0.0 ? 0 : cur.a < 0.0 ? 1 : fine > 0 ? 2 : 3;
    float ts = mode == 0 ? seg_b : mode == 1 ? mid : mode == 2
        ? seg_b + (seg_e - seg_b) * (float(kRefineSamples - fine) + 0.5) / float(kRefineSamples)
        : (closing && seg_e >= b.t_out ? seg_e
           : 0.5 * (seg_e + (closing ? min(seg_e + dt, b.t_out) : seg_e + dt)));
    if (mode != 3 && ts >= b.t_out && !closing) break;  // in the next brick
    // (The next middle may lie in the next brick of the run: read there. A closing brick has
    // none: its run's last read, at t_out, is on its own face.)
    bool beyond = ts >= b.t_out && !closing;
    vec3 off = beyond ? next_page.xyz : b.page.xyz;
    vec3 b_lo = beyond ? vec3(next_c) * cell : b.lo;
    vec3 tcs = ((entry + r.ray * ts) * b.scale + off) * atlas_scale;
    vec2 v = texture(volume, clamp(tcs, (b_lo * b.scale + off) * atlas_scale,
                                   (min(b_lo + cell, box_hi) * b.scale + off) *
                                       atlas_scale)).rg;
    vec4 e = texture(tf_refine, vec2(v.r * tf_map.x + tf_map.y,
                                     mode == 2 ? kFineRow : kPieceRow));
    if (use_stencil != 0 && v.g < 0.5) e = vec4(0.0, 0.0, 0.0, mode == 2 ? 0.0 : 2.0 * piece_of(e));
    float k = (seg_e - seg_b) / dt;
    vec4 c = vec4(0.0);
    vec3 at = tcs;
    bool advance = false;
    if (mode == 0) {
      piece_prev = piece_of(e);
    } else if (mode == 1) {
      cur = e;
    } else if (mode == 2) {
      if (k < 1.0) e = cut_sample(e, k);
      // Sample points, not texture coordinates: a segment's fine samples may lie in two bricks
      // of the run, whose atlas slots differ.
      fine_at += (1.0 - fine_sum.a) * e.a * (entry + r.ray * ts);
      fine_w += (1.0 - fine_sum.a) * e.a;
      fine_sum += (1.0 - fine_sum.a) * e;
      if (--fine == 0) {
        c = fine_sum;
        at = fine_w > 0.0 ? (fine_at / fine_w * b.scale + b.page.xyz) * atlas_scale : tcs;
        advance = true;
      }
    } else {
      ahead = e;
      float piece = piece_of(cur);
      if (piece != piece_prev || piece != piece_of(e)) {
        fine = kRefineSamples;
        fine_sum = vec4(0.0);
        fine_at = vec3(0.0);
        fine_w = 0.0;
      } else {
        c = vec4(cur.rgb, cur.a - 2.0 * piece);
        if (k < 1.0) c = cut_sample(c, k);
        at = ((entry + r.ray * mid) * b.scale + b.page.xyz) * atlas_scale;
        advance = true;
      }
    }
    acc += (1.0 - acc.a) * shade(c, at, b.tc_lo, b.tc_hi);
    if (advance) {
      piece_prev = piece_of(cur);
      cur = ahead;
      seg_b = seg_e;
    }
  }
  t_next = seg_b;
  if (closing) run_open = false;
}
