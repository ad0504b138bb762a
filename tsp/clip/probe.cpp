#include "tsp/clip/probe.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "tsp/core/error.h"

namespace tsp {

namespace {

constexpr double kPi = 3.14159265358979323846;

std::vector<double> numbers(const std::string& text, std::size_t from) {
  std::vector<double> v;
  std::size_t p = from;
  while (p <= text.size()) {
    std::size_t c = text.find(',', p);
    if (c == std::string::npos) c = text.size();
    const std::string part = text.substr(p, c - p);
    char* end = nullptr;
    const double x = std::strtod(part.c_str(), &end);
    if (part.empty() || end != part.c_str() + part.size() || !std::isfinite(x))
      throw UsageError("--probe '" + text + "': '" + part + "' is not a finite number");
    v.push_back(x);
    p = c + 1;
  }
  return v;
}

// Row-major R^T for the rotation about x, then y, then z (probe frame → physical is R).
std::array<double, 9> inverse_rotation(const std::array<double, 3>& deg) {
  const double a = deg[0] * kPi / 180, b = deg[1] * kPi / 180, c = deg[2] * kPi / 180;
  const double ca = std::cos(a), sa = std::sin(a), cb = std::cos(b), sb = std::sin(b),
               cc = std::cos(c), sc = std::sin(c);
  // R = Rz(c) · Ry(b) · Rx(a).
  const double r[9] = {cc * cb, cc * sb * sa - sc * ca, cc * sb * ca + sc * sa,
                       sc * cb, sc * sb * sa + cc * ca, sc * sb * ca - cc * sa,
                       -sb,     cb * sa,                cb * ca};
  return {r[0], r[3], r[6], r[1], r[4], r[7], r[2], r[5], r[8]};
}

std::array<double, 3> apply(const std::array<double, 9>& m, const std::array<double, 3>& v) {
  return {m[0] * v[0] + m[1] * v[1] + m[2] * v[2], m[3] * v[0] + m[4] * v[1] + m[5] * v[2],
          m[6] * v[0] + m[7] * v[1] + m[8] * v[2]};
}

std::array<double, 3> corner(const std::array<double, 3>& lo, const std::array<double, 3>& hi,
                             int c) {
  return {c & 1 ? hi[0] : lo[0], c & 2 ? hi[1] : lo[1], c & 4 ? hi[2] : lo[2]};
}

ClipSide combine(ProbeOp op, const std::vector<ClipSide>& sides) {
  auto all = [&](std::size_t from, ClipSide s) {
    return std::all_of(sides.begin() + std::ptrdiff_t(from), sides.end(),
                       [s](ClipSide x) { return x == s; });
  };
  auto any = [&](std::size_t from, ClipSide s) {
    return std::any_of(sides.begin() + std::ptrdiff_t(from), sides.end(),
                       [s](ClipSide x) { return x == s; });
  };
  switch (op) {
    case ProbeOp::intersect:
      if (any(0, ClipSide::removed)) return ClipSide::removed;
      return all(0, ClipSide::kept) ? ClipSide::kept : ClipSide::straddles;
    case ProbeOp::unite:
      if (any(0, ClipSide::kept)) return ClipSide::kept;
      return all(0, ClipSide::removed) ? ClipSide::removed : ClipSide::straddles;
    case ProbeOp::subtract: {
      // The first minus the union of the others.
      const ClipSide others = sides.size() == 1          ? ClipSide::removed
                              : any(1, ClipSide::kept)    ? ClipSide::kept
                              : all(1, ClipSide::removed) ? ClipSide::removed
                                                          : ClipSide::straddles;
      if (sides[0] == ClipSide::removed || others == ClipSide::kept) return ClipSide::removed;
      if (sides[0] == ClipSide::kept && others == ClipSide::removed) return ClipSide::kept;
      return ClipSide::straddles;
    }
  }
  return ClipSide::straddles;
}

}  // namespace

Probe parse_probe(const std::string& text) {
  const std::size_t colon = text.find(':');
  const std::string kind = text.substr(0, colon);
  const std::string expected =
      "plane:A,B,C,D, sphere:X,Y,Z,R or box:X,Y,Z,HX,HY,HZ[,AX,AY,AZ] (physical coordinates)";
  if (colon == std::string::npos)
    throw UsageError("--probe '" + text + "': expected " + expected);
  const std::vector<double> v = numbers(text, colon + 1);
  Probe p;
  if (kind == "plane" && v.size() == 4) {
    p.kind = Probe::Kind::plane;
    const double n = std::hypot(v[0], v[1], v[2]);
    if (!(n > 0)) throw UsageError("--probe '" + text + "': the plane's normal A,B,C is zero");
    p.centre = {v[0] / n, v[1] / n, v[2] / n};
    p.radius = v[3] / n;
  } else if (kind == "sphere" && v.size() == 4) {
    p.kind = Probe::Kind::sphere;
    p.centre = {v[0], v[1], v[2]};
    p.radius = v[3];
    if (!(p.radius > 0)) throw UsageError("--probe '" + text + "': the radius must be positive");
  } else if (kind == "box" && (v.size() == 6 || v.size() == 9)) {
    p.kind = Probe::Kind::box;
    p.centre = {v[0], v[1], v[2]};
    p.size = {v[3], v[4], v[5]};
    if (v.size() == 9) p.angles = {v[6], v[7], v[8]};
    for (double h : p.size)
      if (!(h > 0)) throw UsageError("--probe '" + text + "': half sizes must be positive");
  } else {
    throw UsageError("--probe '" + text + "': expected " + expected);
  }
  return p;
}

ProbeOp parse_probe_op(const std::string& text) {
  if (text == "intersect") return ProbeOp::intersect;
  if (text == "union") return ProbeOp::unite;
  if (text == "subtract") return ProbeOp::subtract;
  throw UsageError("--probe-op '" + text + "': expected intersect, union or subtract");
}

void move_probe(Probe& p, const std::array<double, 3>& d) {
  if (p.kind == Probe::Kind::plane) {
    p.radius += p.centre[0] * d[0] + p.centre[1] * d[1] + p.centre[2] * d[2];
    return;
  }
  for (int a = 0; a < 3; ++a) p.centre[std::size_t(a)] += d[std::size_t(a)];
}

const char* to_string(ProbeOp op) {
  return op == ProbeOp::intersect ? "intersect" : op == ProbeOp::unite ? "union" : "subtract";
}

std::string to_string(const Probe& p) {
  char buf[256];
  if (p.kind == Probe::Kind::plane)
    std::snprintf(buf, sizeof buf, "plane:%.9g,%.9g,%.9g,%.9g", p.centre[0], p.centre[1],
                  p.centre[2], p.radius);
  else if (p.kind == Probe::Kind::sphere)
    std::snprintf(buf, sizeof buf, "sphere:%.9g,%.9g,%.9g,%.9g", p.centre[0], p.centre[1],
                  p.centre[2], p.radius);
  else
    std::snprintf(buf, sizeof buf, "box:%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g",
                  p.centre[0], p.centre[1], p.centre[2], p.size[0], p.size[1], p.size[2],
                  p.angles[0], p.angles[1], p.angles[2]);
  return buf;
}

ClipRegion::ClipRegion(std::vector<Probe> probes, ProbeOp op, std::array<double, 3> origin,
                       std::array<double, 3> spacing)
    : probes_(std::move(probes)), op_(op), origin_(origin), spacing_(spacing) {
  if (int(probes_.size()) > kMaxProbes)
    throw UsageError("--probe: at most " + std::to_string(kMaxProbes) + " probes, found " +
                     std::to_string(probes_.size()));
  for (const Probe& p : probes_) {
    bool ok = std::isfinite(p.radius);
    for (int a = 0; a < 3; ++a)
      ok &= std::isfinite(p.centre[a]) && std::isfinite(p.size[a]) && std::isfinite(p.angles[a]);
    if (p.kind == Probe::Kind::sphere) ok &= p.radius > 0;
    if (p.kind == Probe::Kind::box) ok &= p.size[0] > 0 && p.size[1] > 0 && p.size[2] > 0;
    if (p.kind == Probe::Kind::plane)
      ok &= std::fabs(std::hypot(p.centre[0], p.centre[1], p.centre[2]) - 1) < 1e-6;
    if (!ok) throw UsageError("--probe " + to_string(p) + ": not a valid probe");
    rotations_.push_back(p.kind == Probe::Kind::box
                             ? inverse_rotation(p.angles)
                             : std::array<double, 9>{1, 0, 0, 0, 1, 0, 0, 0, 1});
  }
  for (int a = 0; a < 3; ++a)
    if (!(spacing_[a] > 0) || !std::isfinite(origin_[a]))
      throw UsageError("clip region: the grid needs finite origin and positive spacing");
}

double ClipRegion::probe_distance(int i, const std::array<double, 3>& p) const {
  const Probe& pr = probes_[std::size_t(i)];
  switch (pr.kind) {
    case Probe::Kind::plane:
      return pr.centre[0] * p[0] + pr.centre[1] * p[1] + pr.centre[2] * p[2] - pr.radius;
    case Probe::Kind::sphere:
      return std::hypot(p[0] - pr.centre[0], p[1] - pr.centre[1], p[2] - pr.centre[2]) - pr.radius;
    case Probe::Kind::box: {
      const std::array<double, 3> q = apply(
          rotations_[std::size_t(i)],
          {p[0] - pr.centre[0], p[1] - pr.centre[1], p[2] - pr.centre[2]});
      double outside = 0, inside = -1e300;
      for (int a = 0; a < 3; ++a) {
        const double d = std::fabs(q[a]) - pr.size[a];
        outside += std::max(d, 0.0) * std::max(d, 0.0);
        inside = std::max(inside, d);
      }
      return std::sqrt(outside) + std::min(inside, 0.0);
    }
  }
  return 0;
}

double ClipRegion::distance(const std::array<double, 3>& p) const {
  if (probes_.empty()) return -1;
  double d0 = probe_distance(0, p);
  if (op_ == ProbeOp::subtract) {
    double others = 1e300;
    for (int i = 1; i < int(probes_.size()); ++i) others = std::min(others, probe_distance(i, p));
    return probes_.size() == 1 ? d0 : std::max(d0, -others);
  }
  for (int i = 1; i < int(probes_.size()); ++i) {
    const double d = probe_distance(i, p);
    d0 = op_ == ProbeOp::intersect ? std::max(d0, d) : std::min(d0, d);
  }
  return d0;
}

bool ClipRegion::kept(const std::array<double, 3>& q) const {
  if (probes_.empty()) return true;
  return distance({origin_[0] + spacing_[0] * q[0], origin_[1] + spacing_[1] * q[1],
                   origin_[2] + spacing_[2] * q[2]}) <= 0;
}

ClipSide ClipRegion::probe_side(int i, const std::array<double, 3>& lo,
                                const std::array<double, 3>& hi) const {
  const Probe& pr = probes_[std::size_t(i)];
  switch (pr.kind) {
    case Probe::Kind::plane: {
      double mn = 1e300, mx = -1e300;
      for (int c = 0; c < 8; ++c) {
        const auto q = corner(lo, hi, c);
        const double s = pr.centre[0] * q[0] + pr.centre[1] * q[1] + pr.centre[2] * q[2];
        mn = std::min(mn, s);
        mx = std::max(mx, s);
      }
      if (mx <= pr.radius) return ClipSide::kept;
      return mn > pr.radius ? ClipSide::removed : ClipSide::straddles;
    }
    case Probe::Kind::sphere: {
      double near2 = 0, far2 = 0;
      for (int a = 0; a < 3; ++a) {
        const double c = pr.centre[std::size_t(a)];
        const double dn = c < lo[a] ? lo[a] - c : c > hi[a] ? c - hi[a] : 0;
        const double df = std::max(std::fabs(c - lo[a]), std::fabs(c - hi[a]));
        near2 += dn * dn;
        far2 += df * df;
      }
      const double r2 = pr.radius * pr.radius;
      if (far2 <= r2) return ClipSide::kept;
      return near2 > r2 ? ClipSide::removed : ClipSide::straddles;
    }
    case Probe::Kind::box: {
      // Corners of the query box in the probe's frame: all inside → kept (the probe is
      // convex); their bounds clear of the probe, or the probe's bounds clear of the query
      // box → removed; else across (conservative).
      const auto& r = rotations_[std::size_t(i)];
      std::array<double, 3> qlo{1e300, 1e300, 1e300}, qhi{-1e300, -1e300, -1e300};
      bool all_inside = true;
      for (int c = 0; c < 8; ++c) {
        const auto pt = corner(lo, hi, c);
        const auto q = apply(r, {pt[0] - pr.centre[0], pt[1] - pr.centre[1], pt[2] - pr.centre[2]});
        for (int a = 0; a < 3; ++a) {
          qlo[a] = std::min(qlo[a], q[a]);
          qhi[a] = std::max(qhi[a], q[a]);
          all_inside &= std::fabs(q[a]) <= pr.size[a];
        }
      }
      if (all_inside) return ClipSide::kept;
      for (int a = 0; a < 3; ++a)
        if (qlo[a] > pr.size[a] || qhi[a] < -pr.size[a]) return ClipSide::removed;
      // The probe's corners in physical space against the query box.
      std::array<double, 3> plo{1e300, 1e300, 1e300}, phi{-1e300, -1e300, -1e300};
      for (int c = 0; c < 8; ++c) {
        const std::array<double, 3> local{c & 1 ? pr.size[0] : -pr.size[0],
                                          c & 2 ? pr.size[1] : -pr.size[1],
                                          c & 4 ? pr.size[2] : -pr.size[2]};
        // R = (R^T)^T: physical = R·local + centre.
        const std::array<double, 3> w{r[0] * local[0] + r[3] * local[1] + r[6] * local[2],
                                      r[1] * local[0] + r[4] * local[1] + r[7] * local[2],
                                      r[2] * local[0] + r[5] * local[1] + r[8] * local[2]};
        for (int a = 0; a < 3; ++a) {
          plo[a] = std::min(plo[a], w[a] + pr.centre[a]);
          phi[a] = std::max(phi[a], w[a] + pr.centre[a]);
        }
      }
      for (int a = 0; a < 3; ++a)
        if (plo[a] > hi[a] || phi[a] < lo[a]) return ClipSide::removed;
      return ClipSide::straddles;
    }
  }
  return ClipSide::straddles;
}

ClipSide ClipRegion::classify(const Aabb& box, double margin) const {
  if (probes_.empty()) return ClipSide::kept;
  std::array<double, 3> lo{}, hi{};
  for (int a = 0; a < 3; ++a) {
    lo[a] = origin_[a] + spacing_[a] * (box.lo[a] - margin);
    hi[a] = origin_[a] + spacing_[a] * (box.hi[a] + margin);
  }
  std::vector<ClipSide> sides;
  for (int i = 0; i < int(probes_.size()); ++i) sides.push_back(probe_side(i, lo, hi));
  return combine(op_, sides);
}

std::vector<ClipSide> ClipRegion::classify_nodes(const Octree& octree, double margin) const {
  if (probes_.empty()) return {};
  std::vector<ClipSide> sides(std::size_t(octree.size()));
  for (int id = 0; id < octree.size(); ++id)
    sides[std::size_t(id)] = classify(geometric_box(octree.node(id).box, octree.dims()), margin);
  return sides;
}

Aabb ClipRegion::probe_bound(int i, const std::array<double, 3>& lo,
                             const std::array<double, 3>& hi) const {
  const Probe& pr = probes_[std::size_t(i)];
  Aabb b = empty_aabb();
  switch (pr.kind) {
    case Probe::Kind::plane: {
      // The kept part of the box is a convex polytope: its vertices are the kept corners and the
      // crossings of the box's 12 edges with the plane.
      double f[8];
      for (int c = 0; c < 8; ++c) {
        const auto p = corner(lo, hi, c);
        f[c] = pr.centre[0] * p[0] + pr.centre[1] * p[1] + pr.centre[2] * p[2] - pr.radius;
        if (f[c] <= 0) grow(b, p);
      }
      for (int c = 0; c < 8; ++c)
        for (int bit = 1; bit < 8; bit <<= 1) {
          const int e = c | bit;
          if (e == c || (f[c] <= 0) == (f[e] <= 0)) continue;
          const auto p = corner(lo, hi, c), q = corner(lo, hi, e);
          const double s = f[c] / (f[c] - f[e]);
          grow(b, {p[0] + s * (q[0] - p[0]), p[1] + s * (q[1] - p[1]), p[2] + s * (q[2] - p[2])});
        }
      return b;
    }
    case Probe::Kind::sphere:
      for (int a = 0; a < 3; ++a) {
        b.lo[a] = pr.centre[a] - pr.radius;
        b.hi[a] = pr.centre[a] + pr.radius;
      }
      break;
    case Probe::Kind::box: {
      const auto& r = rotations_[std::size_t(i)];
      for (int c = 0; c < 8; ++c) {
        const std::array<double, 3> l{c & 1 ? pr.size[0] : -pr.size[0],
                                      c & 2 ? pr.size[1] : -pr.size[1],
                                      c & 4 ? pr.size[2] : -pr.size[2]};
        grow(b, {r[0] * l[0] + r[3] * l[1] + r[6] * l[2] + pr.centre[0],
                 r[1] * l[0] + r[4] * l[1] + r[7] * l[2] + pr.centre[1],
                 r[2] * l[0] + r[5] * l[1] + r[8] * l[2] + pr.centre[2]});
      }
      break;
    }
  }
  return intersection(b, Aabb{lo, hi});
}

Aabb ClipRegion::bound(const Aabb& domain) const {
  if (probes_.empty()) return domain;
  for (int a = 0; a < 3; ++a)
    if (!(spacing_[a] != 0) || !std::isfinite(spacing_[a])) return domain;
  // In physical coordinates (each axis ordered, whatever the spacing's sign), then back.
  std::array<double, 3> lo{}, hi{};
  for (int a = 0; a < 3; ++a) {
    const double x = origin_[a] + spacing_[a] * domain.lo[a], y = origin_[a] + spacing_[a] * domain.hi[a];
    lo[a] = std::min(x, y);
    hi[a] = std::max(x, y);
  }
  Aabb b = op_ == ProbeOp::unite ? empty_aabb() : Aabb{lo, hi};
  const int n = op_ == ProbeOp::subtract ? 1 : int(probes_.size());  // the first, minus others
  for (int i = 0; i < n; ++i) {
    const Aabb p = probe_bound(i, lo, hi);
    if (op_ == ProbeOp::unite)
      unite(b, p);
    else
      b = intersection(b, p);
  }
  if (is_empty(b)) return empty_aabb();
  Aabb out;
  for (int a = 0; a < 3; ++a) {
    const double x = (b.lo[a] - origin_[a]) / spacing_[a], y = (b.hi[a] - origin_[a]) / spacing_[a];
    // A hair wider: rounding must not cut a kept sample off.
    const double hair = 1e-9 * (1 + std::fabs(domain.hi[a] - domain.lo[a]));
    out.lo[a] = std::min(x, y) - hair;
    out.hi[a] = std::max(x, y) + hair;
  }
  return intersection(out, domain);
}

}  // namespace tsp
