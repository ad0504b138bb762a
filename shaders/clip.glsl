// The clip solid (tsp/clip, issue 14), prepended to the ray caster: up to 8 probes — planes,
// spheres, oriented boxes — in physical coordinates, combined by intersection, union or
// subtraction. Per ray the caster finds, analytically, the intervals of ray parameter t where the
// solid is (clip_intervals): a sample is kept when its t lies in one, the solid's surface is at
// their ends, and each end knows the probe whose surface it is (for the normal). With
// clip_surface the ray stops, opaque, where it first meets that surface inside the data: coloured
// by surface_tf at the value there and shaded by the surface normal (TetSplat's view).
// TSP_CLIP (defined before this file) is 0 in the caster without probes: clip_on() is then the
// constant false and all of this is compiled away; 2 in the caster for an intersection, which
// only cuts each ray to kept_interval() once (clip_on() false there too) and draws the surface,
// if on, where the ray enters or leaves that interval. kMaxProbes (tsp::ClipRegion's) is written
// before this file (glsl_constants(), src/render/ray_programs.h).
const float kFar = 1e30;
uniform int clip_count;                // 0: no clipping
uniform int clip_op;                   // 0 intersect, 1 union, 2 subtract (the first minus the rest)
uniform int clip_kind[kMaxProbes];     // 0 plane, 1 sphere, 2 box
uniform vec4 clip_a[kMaxProbes];       // plane: unit normal, offset; sphere: centre, radius; box: centre
uniform vec3 clip_size[kMaxProbes];    // box: half sizes in its own frame
uniform mat3 clip_rot[kMaxProbes];     // box: physical → its frame
uniform vec3 grid_origin, grid_spacing;  // sample coordinates → physical
uniform int clip_surface;              // 1: draw the surface
uniform sampler1D surface_tf;          // its colours (not premultiplied)
uniform vec2 surface_map;              // tf coordinate = normalised scalar · x + y

bool clip_on() { return TSP_CLIP == 1 && clip_count > 0; }

// The ray's kept intervals, sorted, disjoint: [iv_s[k], iv_e[k]] for k < iv_n, with the probe
// whose surface each end lies on (−1: none, the interval runs on).
float iv_s[kMaxProbes], iv_e[kMaxProbes];
int iv_ps[kMaxProbes], iv_pe[kMaxProbes];
int iv_n = 0;

// Probe i's interval along q(t) = q0 + qd·t (physical): [lo, hi], empty when lo > hi.
vec2 probe_interval(int i, vec3 q0, vec3 qd) {
  if (clip_kind[i] == 0) {
    float a = dot(clip_a[i].xyz, qd), b = clip_a[i].w - dot(clip_a[i].xyz, q0);
    if (abs(a) < 1e-12) return b >= 0.0 ? vec2(-kFar, kFar) : vec2(kFar, -kFar);
    return a > 0.0 ? vec2(-kFar, b / a) : vec2(b / a, kFar);
  }
  if (clip_kind[i] == 1) {
    vec3 o = q0 - clip_a[i].xyz;
    float a = dot(qd, qd), b = dot(o, qd), c = dot(o, o) - clip_a[i].w * clip_a[i].w;
    float disc = b * b - a * c;
    if (disc < 0.0) return vec2(kFar, -kFar);
    float s = sqrt(disc);
    return vec2((-b - s) / a, (-b + s) / a);
  }
  vec3 o = clip_rot[i] * (q0 - clip_a[i].xyz), d = clip_rot[i] * qd;
  vec3 inv = 1.0 / (abs(d) + vec3(1e-30)) * sign(d + vec3(1e-30));
  vec3 ta = (-clip_size[i] - o) * inv, tb = (clip_size[i] - o) * inv;
  vec3 lo = min(ta, tb), hi = max(ta, tb);
  return vec2(max(lo.x, max(lo.y, lo.z)), min(hi.x, min(hi.y, hi.z)));
}

// Appends [s, e] from probes ps, pe to the list, keeping it sorted by start (insertion).
void iv_push(float s, float e, int ps, int pe) {
  if (s > e || iv_n >= kMaxProbes) return;
  int k = iv_n++;
  while (k > 0 && iv_s[k - 1] > s) {
    iv_s[k] = iv_s[k - 1]; iv_e[k] = iv_e[k - 1]; iv_ps[k] = iv_ps[k - 1]; iv_pe[k] = iv_pe[k - 1];
    --k;
  }
  iv_s[k] = s; iv_e[k] = e; iv_ps[k] = ps; iv_pe[k] = pe;
}

// Merges the sorted list's overlapping intervals (their union).
void iv_merge() {
  int m = 0;
  for (int k = 0; k < iv_n; ++k) {
    if (m > 0 && iv_s[k] <= iv_e[m - 1]) {
      if (iv_e[k] > iv_e[m - 1]) { iv_e[m - 1] = iv_e[k]; iv_pe[m - 1] = iv_pe[k]; }
    } else {
      iv_s[m] = iv_s[k]; iv_e[m] = iv_e[k]; iv_ps[m] = iv_ps[k]; iv_pe[m] = iv_pe[k];
      ++m;
    }
  }
  iv_n = m;
}

// The kept intervals of the ray p(t) = entry + ray·t (sample coordinates) over t in [0, len].
void clip_intervals(vec3 entry, vec3 ray, float len) {
  vec3 q0 = grid_origin + grid_spacing * entry, qd = grid_spacing * ray;
  iv_n = 0;
  if (clip_op == 0) {  // intersection: one interval
    float s = -kFar, e = kFar;
    int ps = -1, pe = -1;
    for (int i = 0; i < clip_count; ++i) {
      vec2 v = probe_interval(i, q0, qd);
      if (v.x > s) { s = v.x; ps = i; }
      if (v.y < e) { e = v.y; pe = i; }
    }
    iv_push(s, e, ps, pe);
  } else if (clip_op == 1) {  // union
    for (int i = 0; i < clip_count; ++i) {
      vec2 v = probe_interval(i, q0, qd);
      iv_push(v.x, v.y, i, i);
    }
    iv_merge();
  } else {  // the first minus the union of the others
    for (int i = 1; i < clip_count; ++i) {
      vec2 v = probe_interval(i, q0, qd);
      iv_push(v.x, v.y, i, i);
    }
    iv_merge();
    float cs[kMaxProbes], ce[kMaxProbes];
    int cps[kMaxProbes], cpe[kMaxProbes];
    int cn = iv_n;
    for (int k = 0; k < cn; ++k) { cs[k] = iv_s[k]; ce[k] = iv_e[k]; cps[k] = iv_ps[k]; cpe[k] = iv_pe[k]; }
    vec2 a = probe_interval(0, q0, qd);
    float s = a.x;
    int ps = 0;
    iv_n = 0;
    for (int k = 0; k < cn && s <= a.y; ++k) {
      if (ce[k] < s) continue;
      if (cs[k] > a.y) break;
      iv_push(s, min(cs[k], a.y), ps, cs[k] < a.y ? cps[k] : 0);
      if (ce[k] > s) { s = ce[k]; ps = cpe[k]; }
    }
    iv_push(s, a.y, ps, 0);
  }
}

// The intersection's kept interval of the ray p(t) = entry + ray·t (sample coordinates): the
// largest start and the smallest end over the probes (empty when start > end), and the probes
// whose surfaces they lie on. No arrays.
vec2 kept_interval(vec3 entry, vec3 ray, out int ps, out int pe) {
  vec3 q0 = grid_origin + grid_spacing * entry, qd = grid_spacing * ray;
  vec2 kept = vec2(-kFar, kFar);
  ps = 0;
  pe = 0;
  for (int i = 0; i < clip_count; ++i) {
    vec2 v = probe_interval(i, q0, qd);
    if (v.x > kept.x) { kept.x = v.x; ps = i; }
    if (v.y < kept.y) { kept.y = v.y; pe = i; }
  }
  return kept;
}

// Probe i's outward unit normal at physical point q.
vec3 probe_normal(int i, vec3 q) {
  if (clip_kind[i] == 0) return clip_a[i].xyz;
  if (clip_kind[i] == 1) return normalize(q - clip_a[i].xyz);
  vec3 l = clip_rot[i] * (q - clip_a[i].xyz), r = abs(l) / clip_size[i];
  vec3 n = r.x >= r.y && r.x >= r.z ? vec3(sign(l.x), 0, 0)
         : r.y >= r.z                ? vec3(0, sign(l.y), 0)
                                     : vec3(0, 0, sign(l.z));
  return transpose(clip_rot[i]) * n;
}
