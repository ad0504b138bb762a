#include "tsp/frame/refine.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

namespace tsp {

namespace detail {

using Colour = std::array<double, 4>;

// The TF's entries premultiplied, opacity corrected for `spacing` (spec §9).
std::vector<Colour> premultiplied(const TransferFunction& tf, double spacing) {
  std::vector<Colour> c;
  c.reserve(std::size_t(tf.size()));
  for (const Rgba& e : tf.entries()) {
    const double a = corrected_opacity(e.a, spacing);
    c.push_back({e.r * a, e.g * a, e.b * a, a});
  }
  return c;
}

// The largest distance, in any channel, of an entry in (a, b) from the chord from a to b.
double chord_deviation(const std::vector<Colour>& c, std::size_t a, std::size_t b) {
  double worst = 0;
  for (std::size_t i = a + 1; i < b; ++i) {
    const double t = double(i - a) / double(b - a);
    for (std::size_t ch = 0; ch < 4; ++ch)
      worst = std::max(worst, std::abs(c[i][ch] - ((1 - t) * c[a][ch] + t * c[b][ch])));
  }
  return worst;
}

}  // namespace detail

std::vector<int> tf_pieces(const TransferFunction& tf, double spacing, double tol) {
  assert(spacing > 0 && tol >= 0);
  const std::vector<detail::Colour> c = detail::premultiplied(tf, spacing);
  std::vector<int> piece(c.size(), 0);
  // Greedy: the piece starting at entry a takes entry b while every entry up to b stays within
  // tol of the chord from a to b; the first b that does not fit starts the next piece.
  std::size_t a = 0;
  int id = 0;
  for (std::size_t b = 1; b < c.size(); ++b) {
    if (detail::chord_deviation(c, a, b) > tol) {
      ++id;
      a = b;
    }
    piece[b] = id;
  }
  return piece;
}

}  // namespace tsp
