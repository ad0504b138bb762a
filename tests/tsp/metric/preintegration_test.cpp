// Pre-integration against hand-computed segments: one entry (the point lookup over the length),
// a ramp across two entries (half the length in each, front entry first), symmetry of a ramp's
// opacity, and the table's layout.
#include "tsp/metric/preintegration.h"

#include <gtest/gtest.h>

#include <cmath>

namespace tsp {
namespace {

TransferFunction two_entries(Rgba front, Rgba back) {
  TransferFunction tf({0, 1}, 2);
  tf.set_entry(0, front);
  tf.set_entry(1, back);
  return tf;
}

TEST(Preintegration, ASegmentInsideOneEntryIsThePointLookup) {
  const TransferFunction tf = two_entries({0.2f, 0.4f, 0.6f, 0.1f}, {1, 1, 1, 0.5f});
  const Rgba c = integrate_segment(tf, 0.1, 0.3, 4.0);
  const double a = 1 - std::pow(0.9, 4.0);
  EXPECT_NEAR(c.a, a, 1e-6);
  EXPECT_NEAR(c.r, 0.2 * a, 1e-6);
  EXPECT_NEAR(c.b, 0.6 * a, 1e-6);
}

TEST(Preintegration, ARampAcrossTwoEntriesCompositesThemFrontToBack) {
  const Rgba red{1, 0, 0, 0.2f}, blue{0, 0, 1, 0.4f};
  const TransferFunction tf = two_entries(red, blue);
  const double len = 6;
  // u from 0.25 to 0.75: half the ramp (3 voxels) in each entry, red in front.
  const Rgba c = integrate_segment(tf, 0.25, 0.75, len);
  const double ar = 1 - std::pow(0.8, 3.0), ab = 1 - std::pow(0.6, 3.0);
  EXPECT_NEAR(c.r, ar, 1e-6);
  EXPECT_NEAR(c.b, (1 - ar) * ab, 1e-6);
  EXPECT_NEAR(c.a, 1 - (1 - ar) * (1 - ab), 1e-6);
  // Reversed, blue is in front; the opacity is the same.
  const Rgba d = integrate_segment(tf, 0.75, 0.25, len);
  EXPECT_NEAR(d.b, ab, 1e-6);
  EXPECT_NEAR(d.r, (1 - ab) * ar, 1e-6);
  EXPECT_NEAR(d.a, c.a, 1e-6);
}

TEST(Preintegration, TheTableHoldsEverySegmentBetweenEntryCentresFrontFastest) {
  TransferFunction tf({0, 1}, 8);
  for (int j = 0; j < 8; ++j) tf.set_entry(j, {j / 7.f, 0.5f, 1 - j / 7.f, 0.05f * float(j)});
  const std::vector<Rgba> table = preintegrate(tf, 2.0, 2);
  ASSERT_EQ(table.size(), 64u);
  for (int f = 0; f < 8; ++f)
    for (int b = 0; b < 8; ++b) {
      const Rgba want = integrate_segment(tf, (f + 0.5) / 8, (b + 0.5) / 8, 2.0);
      const Rgba& got = table[std::size_t(f + 8 * b)];
      EXPECT_FLOAT_EQ(got.r, want.r) << f << "," << b;
      EXPECT_FLOAT_EQ(got.a, want.a) << f << "," << b;
    }
}

}  // namespace
}  // namespace tsp
