// Compiled once per SIMD target by Highway's foreach_target (see cpu_batch.h).
#include "render/cpu_batch.h"

#include <limits>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "render/cpu_batch.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>
#include <hwy/contrib/math/math-inl.h>

HWY_BEFORE_NAMESPACE();
namespace tspgl::detail::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using D = hn::CappedTag<float, kMaxBatch>;
using DI = hn::RebindToSigned<D>;
using V = hn::Vec<D>;
using VI = hn::Vec<DI>;

struct V3 {
  V x, y, z;
};

// The trilinear blend (Texels::fetch) at u with the texels at shift k, lane by lane: each
// x-pair of texels is one 32-bit gather (the texture has a spare texel at its end for the last).
HWY_INLINE V trilinear(const Texels& t, const V3& u, const V3& k) {
  const D d;
  const DI di;
  const VI zero = hn::Zero(di);
  const V fzero = hn::Zero(d);
  // u ≥ 0 (NaN and below 0 read as 0), where truncation is floor.
  const V x = hn::IfThenElse(hn::Ge(u.x, fzero), u.x, fzero);
  const V y = hn::IfThenElse(hn::Ge(u.y, fzero), u.y, fzero);
  const V z = hn::IfThenElse(hn::Ge(u.z, fzero), u.z, fzero);
  const VI fx = hn::ConvertTo(di, x), fy = hn::ConvertTo(di, y), fz = hn::ConvertTo(di, z);
  const V wx = hn::Sub(x, hn::ConvertTo(d, fx)), wy = hn::Sub(y, hn::ConvertTo(d, fy)),
          wz = hn::Sub(z, hn::ConvertTo(d, fz));
  const VI ix = hn::Min(hn::Max(hn::Add(fx, hn::ConvertTo(di, k.x)), zero), hn::Set(di, t.sx - 1));
  const VI iy = hn::Min(hn::Max(hn::Add(fy, hn::ConvertTo(di, k.y)), zero), hn::Set(di, t.sy - 1));
  const VI iz = hn::Min(hn::Max(hn::Add(fz, hn::ConvertTo(di, k.z)), zero), hn::Set(di, t.sz - 1));
  // Byte offsets: texel (ix, iy, iz), and the steps to the next row and slice (0 at the
  // texture's last row or slice: clamp to edge).
  const VI sx = hn::Set(di, t.sx), sy = hn::Set(di, t.sy);
  const VI at = hn::ShiftLeft<1>(hn::Add(ix, hn::Mul(hn::Add(iy, hn::Mul(iz, sy)), sx)));
  const VI dy = hn::IfThenElseZero(hn::Lt(iy, hn::Set(di, t.sy - 1)), hn::Set(di, 2 * t.sx));
  const VI dz = hn::IfThenElseZero(hn::Lt(iz, hn::Set(di, t.sz - 1)), hn::Set(di, 2 * t.sx * t.sy));
  const auto* base = reinterpret_cast<const std::int32_t*>(t.data);
  const VI mask = hn::Set(di, 0xFFFF);
  // An x-pair at the texture's last column reads the next row's first texel as its second: a
  // lane whose weight there is not 0 (u past the texture) takes the first alone.
  const auto last_x = hn::Eq(ix, hn::Set(di, t.sx - 1));
  auto pair = [&](VI offset, V w) {  // lerp of texels x and x + 1 at offset
    const VI v = hn::GatherOffset(di, base, offset);
    const V lo = hn::ConvertTo(d, hn::And(v, mask));
    const V hi = hn::IfThenElse(hn::RebindMask(d, last_x), lo,
                                hn::ConvertTo(d, hn::And(hn::ShiftRight<16>(v), mask)));
    return hn::MulAdd(hn::Sub(hi, lo), w, lo);
  };
  const VI at_z = hn::Add(at, dz);
  const V c00 = pair(at, wx), c10 = pair(hn::Add(at, dy), wx);
  const V c01 = pair(at_z, wx), c11 = pair(hn::Add(at_z, dy), wx);
  const V c0 = hn::MulAdd(hn::Sub(c10, c00), wy, c00), c1 = hn::MulAdd(hn::Sub(c11, c01), wy, c01);
  return hn::Mul(hn::MulAdd(hn::Sub(c1, c0), wz, c0), hn::Set(d, kUnorm16));
}

V3 broadcast(glm::vec3 v) {
  const D d;
  return {hn::Set(d, v.x), hn::Set(d, v.y), hn::Set(d, v.z)};
}

V3 clamp3(const V3& p, const BrickView& b) {
  const D d;
  return {hn::Min(hn::Max(p.x, hn::Set(d, b.lo.x)), hn::Set(d, b.hi.x)),
          hn::Min(hn::Max(p.y, hn::Set(d, b.lo.y)), hn::Set(d, b.hi.y)),
          hn::Min(hn::Max(p.z, hn::Set(d, b.lo.z)), hn::Set(d, b.hi.z))};
}

V& axis_of(V3& p, int a) { return a == 0 ? p.x : a == 1 ? p.y : p.z; }

// One gradient tap (Sampler::tap): the value one texel from u along `axis` (sign ±1), clamped
// into the brick or read from the neighbour beyond the face, and where along the axis it was read.
HWY_INLINE void tap(const Texels& t, const BrickView& b, const V3& p, int axis, float sign, V& value,
         V& where) {
  const D d;
  V3 q = p;
  axis_of(q, axis) = hn::Add(axis_of(q, axis), hn::Set(d, sign));
  const V qa = axis_of(q, axis);
  V3 c = clamp3(q, b);
  const auto up = hn::Gt(qa, hn::Set(d, b.hi[axis]));
  const auto out = hn::Or(up, hn::Lt(qa, hn::Set(d, b.lo[axis])));
  const glm::vec4 bh = b.beyond_hi[std::size_t(axis)], bl = b.beyond_lo[std::size_t(axis)];
  const V use = hn::IfThenElseZero(out, hn::IfThenElse(up, hn::Set(d, bh.w), hn::Set(d, bl.w)));
  V& ca = axis_of(c, axis);
  ca = hn::MulAdd(hn::Sub(qa, ca), use, ca);
  where = ca;
  const V3 k{hn::MulAdd(hn::IfThenElse(up, hn::Set(d, bh.x), hn::Set(d, bl.x)), use, hn::Set(d, b.k.x)),
             hn::MulAdd(hn::IfThenElse(up, hn::Set(d, bh.y), hn::Set(d, bl.y)), use, hn::Set(d, b.k.y)),
             hn::MulAdd(hn::IfThenElse(up, hn::Set(d, bh.z), hn::Set(d, bl.z)), use, hn::Set(d, b.k.z))};
  value = trilinear(t, c, k);
}

// Texels::gradient lane by lane, for lanes whose six taps all lie inside the brick (p ± 1 within
// its box on every axis): the central differences from the 32 texels around p in 16 gathers of
// x-pairs, where the six taps take 24 and their clamping.
HWY_INLINE V3 gradient_stencil(const Texels& t, const V3& u, const V3& k) {
  const D d;
  const DI di;
  const VI fx = hn::ConvertTo(di, u.x), fy = hn::ConvertTo(di, u.y), fz = hn::ConvertTo(di, u.z);
  const V wx = hn::Sub(u.x, hn::ConvertTo(d, fx)), wy = hn::Sub(u.y, hn::ConvertTo(d, fy)),
          wz = hn::Sub(u.z, hn::ConvertTo(d, fz));
  const VI ix = hn::Add(fx, hn::ConvertTo(di, k.x)), iy = hn::Add(fy, hn::ConvertTo(di, k.y)),
           iz = hn::Add(fz, hn::ConvertTo(di, k.z));
  const std::int32_t row = 2 * t.sx, slice = 2 * t.sx * t.sy;  // bytes
  const VI at = hn::ShiftLeft<1>(hn::Add(ix, hn::Mul(hn::Add(iy, hn::Mul(iz, hn::Set(di, t.sy))),
                                                     hn::Set(di, t.sx))));
  // One past the far texel may lie beyond the texture (where its weight is 0): read the one
  // before it instead, as Texels::gradient does.
  const auto x2_out = hn::RebindMask(d, hn::Gt(hn::Add(ix, hn::Set(di, 2)), hn::Set(di, t.sx - 1)));
  const VI dy2 = hn::IfThenElse(hn::Lt(hn::Add(iy, hn::Set(di, 2)), hn::Set(di, t.sy)),
                                hn::Set(di, 2 * row), hn::Set(di, row));
  const VI dz2 = hn::IfThenElse(hn::Lt(hn::Add(iz, hn::Set(di, 2)), hn::Set(di, t.sz)),
                                hn::Set(di, 2 * slice), hn::Set(di, slice));
  const auto* base = reinterpret_cast<const std::int32_t*>(t.data);
  const VI mask = hn::Set(di, 0xFFFF);
  auto lo_of = [&](VI v) { return hn::ConvertTo(d, hn::And(v, mask)); };
  auto hi_of = [&](VI v) { return hn::ConvertTo(d, hn::And(hn::ShiftRight<16>(v), mask)); };
  auto lerp = [](V a, V b, V w) { return hn::MulAdd(hn::Sub(b, a), w, a); };
  struct Row {
    V m1, x0, x1, x2;  // texels x − 1 … x + 2
  };
  auto core = [&](VI o) {
    const VI left = hn::GatherOffset(di, base, hn::Sub(o, hn::Set(di, 2)));
    const VI right = hn::GatherOffset(di, base, hn::Add(o, hn::Set(di, 2)));
    const V x1 = lo_of(right);
    return Row{lo_of(left), hi_of(left), x1, hn::IfThenElse(x2_out, x1, hi_of(right))};
  };
  struct Pair {
    V x0, x1;
  };
  auto pair = [&](VI o) {
    const VI v = hn::GatherOffset(di, base, o);
    return Pair{lo_of(v), hi_of(v)};
  };
  const VI vrow = hn::Set(di, row), vslice = hn::Set(di, slice);
  const VI a10 = hn::Add(at, vrow), a01 = hn::Add(at, vslice), a11 = hn::Add(a01, vrow);
  const Row r00 = core(at), r10 = core(a10), r01 = core(a01), r11 = core(a11);
  // Along x: each core row's differences at x and x + 1, blended with p's weights.
  auto row_x = [&](const Row& r) { return lerp(hn::Sub(r.x1, r.m1), hn::Sub(r.x2, r.x0), wx); };
  const V gx = lerp(lerp(row_x(r00), row_x(r10), wy), lerp(row_x(r01), row_x(r11), wy), wz);
  // Along y (z), at columns x and x + 1 of the core rows o0 and o1 (their here and next rows
  // h, n): the rows one step before and past next read beside them; w along the axis, w_outer
  // across it.
  auto cross_axis = [&](VI o0, VI o1, VI step, VI step2, const Row& h0, const Row& n0,
                        const Row& h1, const Row& n1, V w, V w_outer) {
    const Pair m0 = pair(hn::Sub(o0, step)), m1 = pair(hn::Sub(o1, step));
    const Pair p0 = pair(hn::Add(o0, step2)), p1 = pair(hn::Add(o1, step2));
    auto col = [&](V below, V here, V next, V beyond) {
      return lerp(hn::Sub(next, below), hn::Sub(beyond, here), w);
    };
    return lerp(lerp(col(m0.x0, h0.x0, n0.x0, p0.x0), col(m0.x1, h0.x1, n0.x1, p0.x1), wx),
                lerp(col(m1.x0, h1.x0, n1.x0, p1.x0), col(m1.x1, h1.x1, n1.x1, p1.x1), wx), w_outer);
  };
  const V gy = cross_axis(at, a01, vrow, dy2, r00, r10, r01, r11, wy, wz);
  const V gz = cross_axis(at, a10, vslice, dz2, r00, r01, r10, r11, wz, wy);
  const V scale = hn::Set(d, 0.5f * kUnorm16);
  return {hn::Mul(gx, scale), hn::Mul(gy, scale), hn::Mul(gz, scale)};
}

// Per lane of a run's view (BrickView::run): its brick's box and bits (Sampler::runs), whether
// that brick is textured (`self`: not so only on a low face of an untextured brick) and whether
// its six taps lie in it or in its textured neighbours (`free`: the 32-texel stencil reads what
// the taps would there, the neighbours' texels continuing the brick's in the dense region).
struct RunLanes {
  V lo[3], hi[3];
  VI bits;
  hn::Mask<D> self, free;
};

HWY_INLINE RunLanes run_lanes(const Sampler& smp, const BrickView& b, const V3& p) {
  const D d;
  const DI di;
  const CastScene& s = smp.s;
  const V one = hn::Set(d, 1.f);
  RunLanes l;
  VI cell[3];
  for (int a = 0; a < 3; ++a) {
    const V size = hn::Set(d, float(s.cell[std::size_t(a)]));
    V c = hn::Floor(hn::Div(a == 0 ? p.x : a == 1 ? p.y : p.z, size));
    c = hn::Min(hn::Max(c, hn::Zero(d)), hn::Set(d, float(s.grid[std::size_t(a)] - 1)));
    cell[a] = hn::ConvertTo(di, c);
    l.lo[a] = hn::Mul(c, size);
    l.hi[a] = hn::Min(hn::Add(l.lo[a], size), hn::Set(d, b.hi[a]));
  }
  const VI index = hn::Add(cell[0], hn::Mul(hn::Set(di, s.grid[0]),
                                            hn::Add(cell[1], hn::Mul(hn::Set(di, s.grid[1]), cell[2]))));
  l.bits = hn::GatherIndex(di, smp.runs.data(), index);
  l.self = hn::RebindMask(d, hn::TestBit(l.bits, hn::Set(di, kRunSelf)));
  l.free = l.self;
  for (int a = 0; a < 3; ++a) {
    const V pa = a == 0 ? p.x : a == 1 ? p.y : p.z;
    const auto lo_ok = hn::RebindMask(d, hn::TestBit(l.bits, hn::Set(di, run_bit(a, 0))));
    const auto hi_ok = hn::RebindMask(d, hn::TestBit(l.bits, hn::Set(di, run_bit(a, 1))));
    l.free = hn::And(l.free, hn::Or(hn::Ge(hn::Sub(pa, one), l.lo[a]), lo_ok));
    l.free = hn::And(l.free, hn::Or(hn::Le(hn::Add(pa, one), l.hi[a]), hi_ok));
  }
  return l;
}

// tap() in a run's view, each lane in its own brick: clamped into it, or read on into a textured
// neighbour beyond the face (shift 0 in the dense region).
HWY_INLINE void run_tap(const Texels& t, const RunLanes& l, const V3& p, const V3& k, int axis,
                        float sign, V& value, V& where) {
  const D d;
  const DI di;
  V3 q = p;
  axis_of(q, axis) = hn::Add(axis_of(q, axis), hn::Set(d, sign));
  const V qa = axis_of(q, axis);
  V3 c{hn::Min(hn::Max(q.x, l.lo[0]), l.hi[0]), hn::Min(hn::Max(q.y, l.lo[1]), l.hi[1]),
       hn::Min(hn::Max(q.z, l.lo[2]), l.hi[2])};
  const auto up = hn::Gt(qa, l.hi[axis]);
  const auto down = hn::Lt(qa, l.lo[axis]);
  const auto up_ok = hn::RebindMask(d, hn::TestBit(l.bits, hn::Set(di, run_bit(axis, 1))));
  const auto down_ok = hn::RebindMask(d, hn::TestBit(l.bits, hn::Set(di, run_bit(axis, 0))));
  const auto use = hn::Or(hn::And(up, up_ok), hn::And(down, down_ok));
  V& ca = axis_of(c, axis);
  ca = hn::IfThenElse(use, qa, ca);
  where = ca;
  value = trilinear(t, c, k);
}

// The gradient's central differences of a run's lanes: the stencil when every lit lane is free,
// else the six taps lane by lane in its own brick.
HWY_INLINE void run_gradient(const Sampler& smp, const BrickView& b, const RunLanes& l,
                             const V3& p, const hn::Mask<D>& lit, V grad[3]) {
  const D d;
  const V3 k = broadcast(b.k);
  if (hn::AllTrue(d, hn::Or(l.free, hn::Not(lit)))) {
    // Lanes not free (unlit) read at the first free lane's place: valid texels, never used.
    const intptr_t first = hn::FindFirstTrue(d, l.free);
    alignas(64) float px[kMaxBatch], py[kMaxBatch], pz[kMaxBatch];
    hn::Store(p.x, d, px);
    hn::Store(p.y, d, py);
    hn::Store(p.z, d, pz);
    const std::size_t f = first < 0 ? 0 : std::size_t(first);
    const V3 q{hn::IfThenElse(l.free, p.x, hn::Set(d, px[f])),
               hn::IfThenElse(l.free, p.y, hn::Set(d, py[f])),
               hn::IfThenElse(l.free, p.z, hn::Set(d, pz[f]))};
    const V3 g = gradient_stencil(smp.tex, q, k);
    grad[0] = g.x;
    grad[1] = g.y;
    grad[2] = g.z;
    return;
  }
  for (int axis = 0; axis < 3; ++axis) {
    V fv, fp, bv, bp;
    run_tap(smp.tex, l, p, k, axis, 1.f, fv, fp);
    run_tap(smp.tex, l, p, k, axis, -1.f, bv, bp);
    grad[axis] = hn::Div(hn::Sub(fv, bv), hn::Max(hn::Sub(fp, bp), hn::Set(d, 1e-3f)));
  }
}

// x^power by squaring (Sampler::specular_power for whole powers below 64).
V power(V x, int n) {
  const D d;
  V r = hn::Set(d, 1.f);
  for (; n > 0; n >>= 1, x = hn::Mul(x, x))
    if (n & 1) r = hn::Mul(r, x);
  return r;
}

// Blinn–Phong of colours (r, g, b, a) from their gradients (Sampler::shade after the gradient).
void light_lanes(const Sampler& smp, V grad[3], V& r, V& g, V& bl, const V& a) {
  const D d;
  const CastScene& s = smp.s;
  for (int axis = 0; axis < 3; ++axis) grad[axis] = hn::Mul(grad[axis], hn::Set(d, s.inv_voxel[axis]));
  const V len2 = hn::MulAdd(grad[0], grad[0], hn::MulAdd(grad[1], grad[1], hn::Mul(grad[2], grad[2])));
  const V len = hn::Sqrt(len2);
  const V dot = hn::MulAdd(grad[0], hn::Set(d, s.light_dir.x),
                           hn::MulAdd(grad[1], hn::Set(d, s.light_dir.y),
                                      hn::Mul(grad[2], hn::Set(d, s.light_dir.z))));
  const V ndl = hn::Div(hn::Abs(dot), hn::Max(len, hn::Set(d, 1e-30f)));
  const V diffuse = hn::MulAdd(hn::Set(d, s.phong.y), ndl, hn::Set(d, s.phong.x));
  V spec;
  const float w = s.phong.w;
  if (w == float(int(w)) && w >= 0.f && w < 64.f) {
    spec = power(ndl, int(w));
  } else {  // (not the default): lane by lane
    alignas(64) float lanes[kMaxBatch];
    hn::Store(ndl, d, lanes);
    for (size_t i = 0; i < hn::Lanes(d); ++i) lanes[i] = std::pow(lanes[i], w);
    spec = hn::Load(d, lanes);
  }
  const V white = hn::Mul(hn::Mul(hn::Set(d, s.phong.z), spec), a);
  // smoothstep(0, kFlatGradient, len)
  const V tt = hn::Min(hn::Max(hn::Div(len, hn::Set(d, kFlatGradient)), hn::Zero(d)), hn::Set(d, 1.f));
  const V fade = hn::Mul(hn::Mul(tt, tt), hn::NegMulAdd(hn::Set(d, 2.f), tt, hn::Set(d, 3.f)));
  const auto lit_mask = hn::Gt(a, hn::Zero(d));
  auto light = [&](V c) {
    const V lit = hn::MulAdd(c, diffuse, white);
    return hn::IfThenElse(lit_mask, hn::MulAdd(hn::Sub(lit, c), fade, c), c);
  };
  r = light(r);
  g = light(g);
  bl = light(bl);
}

// shade_lanes in a run's view; a lit lane on a low face of an untextured brick (its own brick
// is the textured one below: Sampler::lane_view) is lit by Sampler::shade.
void shade_run_lanes(const Sampler& smp, const BrickView& b, const V3& p, V& r, V& g, V& bl,
                     const V& a) {
  const D d;
  const DI di;
  const RunLanes l = run_lanes(smp, b, p);
  const auto lit = hn::Gt(a, hn::Zero(d));
  const auto slow = hn::AndNot(l.self, lit);
  const bool any_slow = !hn::AllFalse(d, slow);
  alignas(64) float cr[kMaxBatch], cg[kMaxBatch], cb[kMaxBatch], ca[kMaxBatch];
  alignas(64) std::int32_t one_by_one[kMaxBatch];
  // (The colours before lighting, for the slow lanes.)
  hn::Store(r, d, cr);
  hn::Store(g, d, cg);
  hn::Store(bl, d, cb);
  hn::Store(a, d, ca);
  hn::Store(hn::VecFromMask(di, hn::RebindMask(di, slow)), di, one_by_one);
  V grad[3];
  run_gradient(smp, b, l, p, hn::And(lit, l.self), grad);
  light_lanes(smp, grad, r, g, bl, a);
  if (!any_slow) return;
  alignas(64) float px[kMaxBatch], py[kMaxBatch], pz[kMaxBatch];
  alignas(64) float lr[kMaxBatch], lg[kMaxBatch], lb[kMaxBatch];
  hn::Store(p.x, d, px);
  hn::Store(p.y, d, py);
  hn::Store(p.z, d, pz);
  hn::Store(r, d, lr);
  hn::Store(g, d, lg);
  hn::Store(bl, d, lb);
  for (size_t i = 0; i < hn::Lanes(d); ++i) {
    if (!one_by_one[i]) continue;
    const glm::vec4 c =
        smp.shade(glm::vec4(cr[i], cg[i], cb[i], ca[i]), glm::vec3(px[i], py[i], pz[i]), b);
    lr[i] = c.r;
    lg[i] = c.g;
    lb[i] = c.b;
  }
  r = hn::Load(d, lr);
  g = hn::Load(d, lg);
  bl = hn::Load(d, lb);
}

// Sampler::shade lane by lane on colours (r, g, b, a) at positions p.
void shade_lanes(const Sampler& smp, const BrickView& b, const V3& p, V& r, V& g, V& bl,
                 const V& a) {
  if (b.run) {
    shade_run_lanes(smp, b, p, r, g, bl, a);
    return;
  }
  const D d;
  // A batch whose taps all lie inside the brick takes the 32-texel stencil; one with a lane
  // near a face the six taps, clamped or read from the neighbour brick. (Mixing the two lane by
  // lane costs both: half of the shock's lit batches have a lane within a texel of a face.)
  const V one = hn::Set(d, 1.f);
  auto free_axis = [&](const V& c, float lo, float hi) {
    return hn::And(hn::Ge(hn::Sub(c, one), hn::Set(d, lo)), hn::Le(hn::Add(c, one), hn::Set(d, hi)));
  };
  const auto free = hn::And(hn::And(free_axis(p.x, b.lo.x, b.hi.x), free_axis(p.y, b.lo.y, b.hi.y)),
                            free_axis(p.z, b.lo.z, b.hi.z));
  V grad[3];
  if (hn::AllTrue(d, free)) {
    const V3 g = gradient_stencil(smp.tex, p, broadcast(b.k));
    grad[0] = g.x;
    grad[1] = g.y;
    grad[2] = g.z;
  } else {
    for (int axis = 0; axis < 3; ++axis) {
      V fv, fp, bv, bp;
      tap(smp.tex, b, p, axis, 1.f, fv, fp);
      tap(smp.tex, b, p, axis, -1.f, bv, bp);
      grad[axis] = hn::Div(hn::Sub(fv, bv), hn::Max(hn::Sub(fp, bp), hn::Set(d, 1e-3f)));
    }
  }
  light_lanes(smp, grad, r, g, bl, a);
}

// The n positions from `start` (a multiple of the lanes); unused lanes repeat the first
// position (valid reads).
HWY_INLINE V3 load_positions(const Positions& p, int start, int n) {
  const D d;
  const auto m = hn::FirstN(d, size_t(n));
  return {hn::IfThenElse(m, hn::Load(d, p.x + start), hn::Set(d, p.x[start])),
          hn::IfThenElse(m, hn::Load(d, p.y + start), hn::Set(d, p.y[start])),
          hn::IfThenElse(m, hn::Load(d, p.z + start), hn::Set(d, p.z[start]))};
}

void SampleBatch(const Sampler& smp, const BrickView& b, const float* row, const Positions& pos,
                 int n, bool shade, Colours& out) {
  const D d;
  const DI di;
  const size_t lanes = hn::Lanes(d);
  for (int start = 0; start < n; start += int(lanes)) {
    const int m = std::min(int(lanes), n - start);
    const V3 p = load_positions(pos, start, m);
    const V v = trilinear(smp.tex, clamp3(p, b), broadcast(b.k));
    const CastTables& tf = smp.s.tf;
    const V u = hn::MulAdd(v, hn::Set(d, tf.scale), hn::Set(d, tf.offset));
    const V k = hn::Max(hn::Mul(u, hn::Set(d, float(tf.entries))), hn::Set(d, -1.f));
    const VI i = hn::Min(hn::Max(hn::ConvertTo(di, k), hn::Zero(di)), hn::Set(di, tf.entries - 1));
    const VI i4 = hn::ShiftLeft<2>(i);
    V r = hn::GatherIndex(d, row, i4);
    V g = hn::GatherIndex(d, row, hn::Add(i4, hn::Set(di, 1)));
    V bl = hn::GatherIndex(d, row, hn::Add(i4, hn::Set(di, 2)));
    const V a = hn::GatherIndex(d, row, hn::Add(i4, hn::Set(di, 3)));
    if (shade && smp.s.shade && !hn::AllTrue(d, hn::Le(a, hn::Zero(d))))
      shade_lanes(smp, b, p, r, g, bl, a);
    // (kMaxBatch is a multiple of the lanes: whole vectors fit; lanes past n are not read.)
    hn::Store(r, d, out.r + start);
    hn::Store(g, d, out.g + start);
    hn::Store(bl, d, out.b + start);
    hn::Store(a, d, out.a + start);
  }
}

void ShadeBatch(const Sampler& smp, const BrickView& b, const Positions& pos, int n, Colours& c) {
  const D d;
  const size_t lanes = hn::Lanes(d);
  for (int start = 0; start < n; start += int(lanes)) {
    const int m = std::min(int(lanes), n - start);
    // Lanes past n are transparent: never lit, never read back.
    const V a = hn::IfThenElseZero(hn::FirstN(d, size_t(m)), hn::Load(d, c.a + start));
    if (hn::AllTrue(d, hn::Le(a, hn::Zero(d)))) continue;
    V r = hn::Load(d, c.r + start), g = hn::Load(d, c.g + start), bl = hn::Load(d, c.b + start);
    shade_lanes(smp, b, load_positions(pos, start, m), r, g, bl, a);
    hn::Store(r, d, c.r + start);
    hn::Store(g, d, c.g + start);
    hn::Store(bl, d, c.b + start);
  }
}

// cut_sample lane by lane: each colour standing for k of its segment, opacity 1 − (1 − α)^k
// (as exp(k·log(1 − α))), premultiplied colour scaled with it; transparent lanes unchanged.
void CutBatch(const float* k, int n, Colours& c) {
  const D d;
  const size_t lanes = hn::Lanes(d);
  const V one = hn::Set(d, 1.f), tiny = hn::Set(d, 1e-30f);
  for (int start = 0; start < n; start += int(lanes)) {
    const int m = std::min(int(lanes), n - start);
    const auto live = hn::FirstN(d, size_t(m));
    const V a = hn::IfThenElseZero(live, hn::Load(d, c.a + start));
    const auto lit = hn::Gt(a, hn::Zero(d));
    if (hn::AllFalse(d, lit)) continue;
    const V kv = hn::IfThenElse(live, hn::Load(d, k + start), one);
    const V rest = hn::Max(hn::Sub(one, a), tiny);
    const V cut = hn::Sub(one, hn::Exp(d, hn::Mul(kv, hn::Log(d, rest))));
    const V scale = hn::Div(cut, hn::IfThenElse(lit, a, one));
    auto apply = [&](float* ch) {
      const V v = hn::Load(d, ch + start);
      hn::Store(hn::IfThenElse(lit, hn::Mul(v, scale), v), d, ch + start);
    };
    apply(c.r);
    apply(c.g);
    apply(c.b);
    hn::Store(hn::IfThenElse(lit, cut, hn::Load(d, c.a + start)), d, c.a + start);
  }
}

}  // namespace tspgl::detail::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace tspgl::detail {

HWY_EXPORT(SampleBatch);
HWY_EXPORT(ShadeBatch);
HWY_EXPORT(CutBatch);

bool batch_ready(const Sampler& smp) {
  if (!smp.tex.data || smp.tex.channels != 1) return false;
  const std::int64_t texels = std::int64_t(smp.tex.sx) * smp.tex.sy * smp.tex.sz;
  return 2 * (texels + kHostVolumePad) < std::int64_t(std::numeric_limits<std::int32_t>::max());
}

void sample_batch(const Sampler& smp, const BrickView& b, const float* row, const Positions& p,
                  int n, bool shade, Colours& out) {
  HWY_DYNAMIC_DISPATCH(SampleBatch)(smp, b, row, p, n, shade, out);
}

void shade_batch(const Sampler& smp, const BrickView& b, const Positions& p, int n, Colours& c) {
  HWY_DYNAMIC_DISPATCH(ShadeBatch)(smp, b, p, n, c);
}

void cut_batch(const float* k, int n, Colours& c) { HWY_DYNAMIC_DISPATCH(CutBatch)(k, n, c); }

}  // namespace tspgl::detail
#endif  // HWY_ONCE
