// One sample of the CPU ray caster (cpu_caster.h), written as shaders/sample_tf.glsl writes it
// for the GL caster: a trilinear read of 16-bit texels as GL's linear filter reads them (texel
// centres at +½, clamp to edge), the TF's nearest lookup, the opacity correction of a cut
// segment, and Blinn–Phong from central differences that read the neighbour brick beyond a face.
// Positions are a brick's sample coordinates scaled to its texels (u = p · scale: texel i of the
// brick's lattice lies at u = its origin · scale + i) and a brick's texels start at the integer
// shift k (GL's texel coordinate is u + k + ½). Split so, the trilinear weights come from u
// alone and never depend on where the brick sits in the atlas: the same frame gives the same
// bytes whatever the slots (GL's weights round with the slot's texture coordinate).
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "render/cpu_caster.h"
#include "render/ray_constants.h"

namespace tspgl::detail {

// The constants both casters share (ray_constants.h; the GLSL gets the same values).
using ray::kClipFlag;
using ray::kFlatGradient;
using ray::kLevelRowUnit;
using ray::kNudge;
using ray::kOpaque;
/// 1 / 65535: a 16-bit unsigned normalised texel as GL reads it.
inline constexpr float kUnorm16 = 1.f / 65535.f;

/// The 16-bit texels of one texture.
struct Texels {
  const std::uint16_t* data = nullptr;
  int sx = 0, sy = 0, sz = 0, channels = 1;
  explicit Texels(const HostVolume* v) {
    if (!v || v->empty()) return;
    data = v->texels.data();
    sx = v->size[0];
    sy = v->size[1];
    sz = v->size[2];
    channels = v->channels;
  }

  /// Index of texel (x, y, z), channel 0.
  std::size_t index(int x, int y, int z) const {
    return (std::size_t(x) + std::size_t(sx) * (std::size_t(y) + std::size_t(sy) * std::size_t(z))) *
           std::size_t(channels);
  }

  /// The trilinear blend of channel ch at u with the brick's texels at shift k (GL_LINEAR,
  /// clamped to edge); u is never below 0 (positions are clamped into a brick's box first; a
  /// stray one, NaN or below 0, reads as 0).
  [[gnu::always_inline]] float fetch(glm::vec3 u, glm::vec3 k, int ch = 0) const {
    const float x = u.x >= 0.f ? u.x : 0.f, y = u.y >= 0.f ? u.y : 0.f, z = u.z >= 0.f ? u.z : 0.f;
    const int fx = int(x), fy = int(y), fz = int(z);  // x, y, z ≥ 0: truncation is floor
    const float wx = x - float(fx), wy = y - float(fy), wz = z - float(fz);
    const int ix = std::clamp(fx + int(k.x), 0, sx - 1), iy = std::clamp(fy + int(k.y), 0, sy - 1),
              iz = std::clamp(fz + int(k.z), 0, sz - 1);
    const std::ptrdiff_t dx = ix + 1 < sx ? channels : 0;
    const std::ptrdiff_t dy = iy + 1 < sy ? std::ptrdiff_t(sx) * channels : 0;
    const std::ptrdiff_t dz = iz + 1 < sz ? std::ptrdiff_t(sx) * sy * channels : 0;
    const std::uint16_t* q = data + index(ix, iy, iz) + ch;
    const float c00 = float(q[0]) + (float(q[dx]) - float(q[0])) * wx;
    const float c10 = float(q[dy]) + (float(q[dy + dx]) - float(q[dy])) * wx;
    const float c01 = float(q[dz]) + (float(q[dz + dx]) - float(q[dz])) * wx;
    const float c11 = float(q[dz + dy]) + (float(q[dz + dy + dx]) - float(q[dz + dy])) * wx;
    const float c0 = c00 + (c10 - c00) * wy, c1 = c01 + (c11 - c01) * wy;
    return (c0 + (c1 - c0) * wz) * kUnorm16;
  }

  /// The central differences of the trilinear field one texel either side of u along each
  /// axis, over 2 texels (shade's gradient where no tap is clamped: lo + 1 ≤ p ≤ hi − 1), from
  /// the 32 texels around p — each difference is the trilinear blend, with p's weights, of the
  /// texels' own differences. Asserts the texels lie inside.
  [[gnu::always_inline]] glm::vec3 gradient(glm::vec3 u, glm::vec3 k) const {
    const int fx = int(u.x), fy = int(u.y), fz = int(u.z);
    const float wx = u.x - float(fx), wy = u.y - float(fy), wz = u.z - float(fz);
    const int ix = fx + int(k.x), iy = fy + int(k.y), iz = fz + int(k.z);
    assert(ix >= 1 && iy >= 1 && iz >= 1 && ix + 2 < sx + 1 && iy + 2 < sy + 1 && iz + 2 < sz + 1);
    const std::ptrdiff_t dx = channels, dy = std::ptrdiff_t(sx) * channels,
                         dz = std::ptrdiff_t(sx) * sy * channels;
    // One past the far texel may lie beyond the texture where its weight is 0: read the texel
    // before it instead.
    const std::ptrdiff_t dx2 = ix + 2 < sx ? 2 * dx : dx, dy2 = iy + 2 < sy ? 2 * dy : dy,
                         dz2 = iz + 2 < sz ? 2 * dz : dz;
    const std::uint16_t* q = data + index(ix, iy, iz);
    auto v = [&](std::ptrdiff_t o) { return float(q[o]); };
    auto lerp = [](float a, float b, float w) { return a + (b - a) * w; };
    // Along x: rows (y, z) ∈ {0, 1}², differences at x0 and x0 + 1.
    auto row_x = [&](std::ptrdiff_t o) {
      return lerp(v(o + dx) - v(o - dx), v(o + dx2) - v(o), wx);
    };
    auto row_y = [&](std::ptrdiff_t o) {
      return lerp(v(o + dy) - v(o - dy), v(o + dy2) - v(o), wy);
    };
    auto row_z = [&](std::ptrdiff_t o) {
      return lerp(v(o + dz) - v(o - dz), v(o + dz2) - v(o), wz);
    };
    const float gx = lerp(lerp(row_x(0), row_x(dy), wy), lerp(row_x(dz), row_x(dz + dy), wy), wz);
    const float gy = lerp(lerp(row_y(0), row_y(dx), wx), lerp(row_y(dz), row_y(dz + dx), wx), wz);
    const float gz = lerp(lerp(row_z(0), row_z(dx), wx), lerp(row_z(dy), row_z(dy + dx), wx), wy);
    return glm::vec3(gx, gy, gz) * (0.5f * kUnorm16);
  }

  /// gradient()'s component along `axis` alone, where only that axis' taps are unclamped (p
  /// inside its texel box, p ± 1 along the axis too).
  [[gnu::always_inline]] float axis_difference(glm::vec3 u, glm::vec3 k, int axis) const {
    const glm::ivec3 f(int(u.x), int(u.y), int(u.z));
    const glm::vec3 w = u - glm::vec3(f);
    const glm::ivec3 i = f + glm::ivec3(k);
    const std::array<std::ptrdiff_t, 3> stride{std::ptrdiff_t(channels),
                                               std::ptrdiff_t(sx) * channels,
                                               std::ptrdiff_t(sx) * sy * channels};
    const std::array<int, 3> size{sx, sy, sz};
    const int b = axis == 0 ? 1 : 0, c = axis == 2 ? 1 : 2;  // the other two axes
    const std::ptrdiff_t da = stride[std::size_t(axis)];
    const std::ptrdiff_t da2 = i[axis] + 2 < size[std::size_t(axis)] ? 2 * da : da;
    const std::ptrdiff_t db = i[b] + 1 < size[std::size_t(b)] ? stride[std::size_t(b)] : 0;
    const std::ptrdiff_t dc = i[c] + 1 < size[std::size_t(c)] ? stride[std::size_t(c)] : 0;
    const std::uint16_t* q = data + index(i.x, i.y, i.z);
    auto lerp = [](float u, float v, float t) { return u + (v - u) * t; };
    auto row = [&](std::ptrdiff_t o) {
      return lerp(float(q[o + da]) - float(q[o - da]), float(q[o + da2]) - float(q[o]), w[axis]);
    };
    return lerp(lerp(row(0), row(db), w[b]), lerp(row(dc), row(dc + db), w[b]), w[c]) *
           (0.5f * kUnorm16);
  }
};

/// Entry of a K-entry row for tf coordinate u (GL_NEAREST, clamped).
inline const float* lookup(const float* row, int k, float u) {
  // Truncation, not floor: they differ only below 0, which the clamp sends to 0 either way.
  const int i = std::clamp(int(std::max(u * float(k), -1.f)), 0, k - 1);
  return row + 4 * i;
}

inline glm::vec4 entry(const float* e) { return {e[0], e[1], e[2], e[3]}; }

/// A sample standing for k (≤ 1) of its segment: opacity 1 − (1 − α)^k, premultiplied.
inline glm::vec4 cut_sample(glm::vec4 s, float k) {
  if (s.a <= 0.f) return s;
  const float a = 1.f - std::pow(std::max(1.f - s.a, 0.f), k);
  return {glm::vec3(s) * (a / s.a), a};
}

/// What a brick's samples read: its texel box and, per face, the shift to the neighbour
/// brick's texels (w 1 where the neighbour is a level-0 texture, else 0: one-sided).
struct BrickView {
  glm::vec3 lo{0}, hi{0};  ///< the brick's box in u (sample coordinates · scale)
  glm::vec3 k{0};          ///< its texels' integer shift in the texture
  std::array<glm::vec4, 3> beyond_lo{}, beyond_hi{};
  /// A run of full-resolution bricks in the dense region (CastScene::runs): lo..hi bound the
  /// volume, and each sample is lit as its own brick's (Sampler::lane_view).
  bool run = false;
  /// The textured neighbours' texels continue this brick's (shift 0, the dense region): the
  /// gradient's stencil may read across those faces.
  bool contiguous = false;
};

/// Bits of Sampler::runs: the brick is a full-resolution page of the dense region, and which of
/// its six face neighbours (−x, +x, −y, +y, −z, +z) are too.
inline constexpr std::int32_t kRunSelf = 1;
/// The bit of Sampler::runs for the neighbour beyond face `side` (0: low, 1: high) of `axis`.
inline constexpr std::int32_t run_bit(int axis, int side) { return 2 << (2 * axis + side); }

/// The sampler of one cast: texels, tables and lighting.
struct Sampler {
  Texels tex;
  const CastScene& s;
  /// Per brick of the grid, with CastScene::runs: kRunSelf and run_bit()s (empty otherwise).
  std::vector<std::int32_t> runs;
  explicit Sampler(const CastScene& scene) : tex(scene.volume), s(scene) {}

  /// The view of the brick a run's sample at p lies in (on a face, a textured one), with its
  /// textured neighbours contiguous: the view the brick-by-brick walk lit it with.
  BrickView lane_view(const BrickView& run, glm::vec3 p) const {
    const glm::ivec3 grid(s.grid[0], s.grid[1], s.grid[2]);
    const glm::vec3 cell(float(s.cell[0]), float(s.cell[1]), float(s.cell[2]));
    glm::ivec3 c = glm::clamp(glm::ivec3(glm::floor(p / cell)), glm::ivec3(0), grid - 1);
    auto at = [&](glm::ivec3 q) {
      return runs[std::size_t(q.x) + std::size_t(grid.x) * (std::size_t(q.y) + std::size_t(grid.y) * std::size_t(q.z))];
    };
    if (!(at(c) & kRunSelf)) {  // on a low face of an untextured brick: a textured one below
      // The axes along which p lies on c's low face (one brick further down is possible).
      const glm::bvec3 face(p.x == float(c.x) * cell.x && c.x > 0, p.y == float(c.y) * cell.y && c.y > 0,
                            p.z == float(c.z) * cell.z && c.z > 0);
      for (int m = 1; m < 8; ++m) {  // the bricks below over any of those axes, in turn
        const glm::bvec3 down((m & 1) != 0, (m & 2) != 0, (m & 4) != 0);
        if (glm::any(down && glm::not_(face))) continue;
        const glm::ivec3 q = c - glm::ivec3(down);
        if (at(q) & kRunSelf) {
          c = q;
          break;
        }
      }
    }
    BrickView v;
    v.k = run.k;
    v.lo = glm::vec3(c) * cell;
    v.hi = glm::min(v.lo + cell, run.hi);
    v.contiguous = true;
    const std::int32_t bits = at(c);
    for (int a = 0; a < 3; ++a) {
      v.beyond_lo[std::size_t(a)] = glm::vec4(0.f, 0.f, 0.f, (bits & run_bit(a, 0)) ? 1.f : 0.f);
      v.beyond_hi[std::size_t(a)] = glm::vec4(0.f, 0.f, 0.f, (bits & run_bit(a, 1)) ? 1.f : 0.f);
    }
    return v;
  }

  float tf_coord(float v) const { return v * s.tf.scale + s.tf.offset; }

  /// x^power for the specular term: by squaring when the power is a whole number below 64
  /// (VTK's default 10), std::pow otherwise.
  float specular_power(float x) const {
    const float w = s.phong.w;
    if (w != std::floor(w) || w < 0.f || w >= 64.f) return std::pow(x, w);
    float r = 1.f;
    for (int n = int(w); n > 0; n >>= 1, x *= x)
      if (n & 1) r *= x;
    return r;
  }

  /// One tap of the central differences (gradient_tap in sample_tf.glsl): the scalar one texel
  /// from the sample along `axis` and where along that axis it was read.
  glm::vec2 tap(glm::vec3 q, int axis, const BrickView& b) const {
    glm::vec3 c = glm::clamp(q, b.lo, b.hi);
    const bool up = q[axis] > b.hi[axis];
    const glm::vec4 sh = up ? b.beyond_hi[std::size_t(axis)] : b.beyond_lo[std::size_t(axis)];
    const float use = (up || q[axis] < b.lo[axis]) ? sh.w : 0.f;
    c[axis] = c[axis] + (q[axis] - c[axis]) * use;
    return {tex.fetch(c, b.k + glm::vec3(sh) * use), c[axis]};
  }

  /// c lit at texel position p (shade in sample_tf.glsl).
  glm::vec4 shade(glm::vec4 c, glm::vec3 p, const BrickView& b) const {
    if (!s.shade || c.a <= 0.f) return c;
    if (b.run) return shade(c, p, lane_view(b, p));
    glm::vec3 g;
    glm::bvec3 free_axis = glm::greaterThanEqual(p - 1.f, b.lo) && glm::lessThanEqual(p + 1.f, b.hi);
    if (b.contiguous)  // the stencil reads on into textured neighbours
      for (int a = 0; a < 3; ++a)
        free_axis[a] = (p[a] - 1.f >= b.lo[a] || b.beyond_lo[std::size_t(a)].w > 0.f) &&
                       (p[a] + 1.f <= b.hi[a] || b.beyond_hi[std::size_t(a)].w > 0.f);
    if (glm::all(free_axis)) {
      g = tex.gradient(p, b.k);  // no tap clamped: the 32-texel stencil
    } else {
      const bool inside = glm::all(glm::greaterThanEqual(p, b.lo)) && glm::all(glm::lessThanEqual(p, b.hi));
      for (int a = 0; a < 3; ++a) {
        if (inside && free_axis[a]) {  // this axis' taps unclamped
          g[a] = tex.axis_difference(p, b.k, a);
          continue;
        }
        glm::vec3 e(0.f);
        e[a] = 1.f;
        const glm::vec2 f = tap(p + e, a, b), k = tap(p - e, a, b);
        g[a] = (f.x - k.x) / std::max(f.y - k.y, 1e-3f);
      }
    }
    g *= s.inv_voxel;
    const float len = glm::length(g);
    const float ndl = std::abs(glm::dot(g, s.light_dir)) / std::max(len, 1e-30f);
    const glm::vec3 rgb(c);
    const glm::vec3 lit =
        rgb * (s.phong.x + s.phong.y * ndl) + glm::vec3(s.phong.z * specular_power(ndl) * c.a);
    const float w = glm::smoothstep(0.f, kFlatGradient, len);
    return {rgb + (lit - rgb) * w, c.a};
  }

  /// The point lookup at p (sample_point), through `row` (K entries).
  glm::vec4 point(glm::vec3 p, const BrickView& b, const float* row) const {
    const glm::vec3 q = glm::clamp(p, b.lo, b.hi);
    if (s.stencil && tex.fetch(q, b.k, 1) < 0.5f) return glm::vec4(0.f);
    return shade(entry(lookup(row, s.tf.entries, tf_coord(tex.fetch(q, b.k)))), p, b);
  }
};

}  // namespace tspgl::detail
