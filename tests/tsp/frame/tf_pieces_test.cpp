#include "tsp/frame/refine.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

namespace tsp {
namespace {

using Colour = std::array<double, 4>;

// Entry i of tf as the renderer's lookup texture holds it: premultiplied, its opacity corrected
// for `spacing` (independently of the code under test).
Colour premultiplied(const TransferFunction& tf, int i, double spacing) {
  const Rgba& e = tf.entries()[std::size_t(i)];
  const double a = 1 - std::pow(1 - double(e.a), spacing);
  return {e.r * a, e.g * a, e.b * a, a};
}

// Brute force: the largest distance of an entry in [a, b] from the chord from a to b.
double stray(const TransferFunction& tf, int a, int b, double spacing) {
  const Colour ca = premultiplied(tf, a, spacing), cb = premultiplied(tf, b, spacing);
  double worst = 0;
  for (int i = a; i <= b; ++i) {
    const double t = b > a ? double(i - a) / (b - a) : 0;
    const Colour c = premultiplied(tf, i, spacing);
    for (std::size_t k = 0; k < 4; ++k)
      worst = std::max(worst, std::abs(c[k] - ((1 - t) * ca[k] + t * cb[k])));
  }
  return worst;
}

TEST(TfPieces, AStraightTfIsOnePieceAndAStepCutsIt) {
  // A linear ramp in colour with constant opacity is straight: one piece at any tolerance.
  const std::vector<TfPoint> ramp{{0.0, {0, 0, 1, 0.5f}}, {1.0, {1, 0, 0, 0.5f}}};
  const TransferFunction straight = TransferFunction::from_points({0, 1}, ramp, 256);
  const std::vector<int> one = tf_pieces(straight, 0.5, 1e-4);
  EXPECT_EQ(*std::max_element(one.begin(), one.end()), 0);
  // Clear below the middle, opaque above: two pieces, cut at the step.
  const std::vector<TfPoint> step{{0.0, {0, 0, 1, 0}}, {0.499, {0, 0, 1, 0}},
                                  {0.5, {1, 0, 0, 0.9f}}, {1.0, {1, 0, 0, 0.9f}}};
  const TransferFunction stepped = TransferFunction::from_points({0, 1}, step, 256);
  const std::vector<int> two = tf_pieces(stepped, 0.5, 0.05);
  ASSERT_EQ(int(two.size()), 256);
  EXPECT_EQ(two.front(), 0);
  EXPECT_EQ(two.back(), 1);
  const int first_opaque = int(std::find(two.begin(), two.end(), 1) - two.begin());
  EXPECT_GT(stepped.entries()[std::size_t(first_opaque)].a, 0.f);
  EXPECT_EQ(stepped.entries()[std::size_t(first_opaque - 1)].a, 0.f);
}

TEST(TfPieces, EveryPieceStaysNearItsChordAndIsAsLongAsItCanBe) {
  // Random TFs: pieces rise by one from 0; within a piece, every pair of entries has the TF
  // within 2·tol of their chord (what the caster relies on); and no piece could take the first
  // entry of the next one and stay within tol of its chord (greedy, maximal).
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0, 1);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<TfPoint> pts;
    for (int k = 0; k <= 8; ++k) pts.push_back({k / 8.0, {u(rng), u(rng), u(rng), u(rng)}});
    const TransferFunction tf = TransferFunction::from_points({0, 1}, pts, 64);
    const double spacing = 0.25 + 2 * u(rng), tol = 0.01 + 0.1 * u(rng);
    const std::vector<int> piece = tf_pieces(tf, spacing, tol);
    ASSERT_EQ(int(piece.size()), 64);
    EXPECT_EQ(piece[0], 0);
    for (std::size_t i = 1; i < piece.size(); ++i) {
      EXPECT_TRUE(piece[i] == piece[i - 1] || piece[i] == piece[i - 1] + 1) << "entry " << i;
    }
    int start = 0;
    for (int i = 1; i <= 64; ++i) {
      if (i < 64 && piece[std::size_t(i)] == piece[std::size_t(start)]) continue;
      const int end = i - 1;  // the piece is [start, end]
      EXPECT_LE(stray(tf, start, end, spacing), tol + 1e-6) << "trial " << trial;
      for (int a = start; a <= end; ++a)
        for (int b = a; b <= end; ++b)
          EXPECT_LE(stray(tf, a, b, spacing), 2 * tol + 1e-6)
              << "trial " << trial << ", entries " << a << ".." << b;
      if (i < 64) {
        EXPECT_GT(stray(tf, start, i, spacing), tol) << "trial " << trial;
      }
      start = i;
    }
  }
}

}  // namespace
}  // namespace tsp
