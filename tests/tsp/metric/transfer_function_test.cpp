#include "tsp/metric/transfer_function.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "tsp/core/error.h"

namespace tsp {
namespace {

TEST(TransferFunction, EntryCentresAndEntryOfFollowTheSpec) {
  TransferFunction tf({-1, 3}, 8);  // entry width 0.5
  EXPECT_DOUBLE_EQ(tf.entry_value(0), -0.75);
  EXPECT_DOUBLE_EQ(tf.entry_value(7), 2.75);
  EXPECT_EQ(tf.entry_of(-1.0), 0);
  EXPECT_EQ(tf.entry_of(-0.51), 0);
  EXPECT_EQ(tf.entry_of(-0.5), 1);
  EXPECT_EQ(tf.entry_of(2.99), 7);
  EXPECT_EQ(tf.entry_of(3.0), 7);    // the top of the domain belongs to the last entry
  EXPECT_EQ(tf.entry_of(-50.0), 0);  // clamped
  EXPECT_EQ(tf.entry_of(50.0), 7);
  EXPECT_EQ(tf.entry_of(std::nan("")), 0);
  for (int j = 0; j < 8; ++j) EXPECT_EQ(tf.entry_of(tf.entry_value(j)), j);
}

TEST(TransferFunction, RejectsBadDomainsAndSizes) {
  EXPECT_THROW(TransferFunction({1, 1}, 8), UsageError);
  EXPECT_THROW(TransferFunction({2, 1}, 8), UsageError);
  EXPECT_THROW(TransferFunction({0, INFINITY}, 8), UsageError);
  EXPECT_THROW(TransferFunction({0, 1}, 1), UsageError);
  TransferFunction tf({0, 1}, 4);
  EXPECT_THROW(tf.set_domain({1, 0}), UsageError);
}

TEST(TransferFunction, FromPointsInterpolatesLinearlyAndClampsBeyondTheEnds) {
  // Red rises 0 → 1 between x = 2 and x = 6; outside, the end colours hold.
  std::vector<TfPoint> pts = {{6, {1, 0, 0, 1}}, {2, {0, 0, 1, 0}}};    // unsorted on purpose
  TransferFunction tf = TransferFunction::from_points({0, 8}, pts, 8);  // centres 0.5, 1.5, ...
  for (int j = 0; j < 8; ++j) {
    double x = 0.5 + j;
    double t = std::clamp((x - 2) / 4, 0.0, 1.0);
    EXPECT_NEAR(tf.entry(j).r, t, 1e-6) << j;
    EXPECT_NEAR(tf.entry(j).b, 1 - t, 1e-6) << j;
    EXPECT_NEAR(tf.entry(j).a, t, 1e-6) << j;
  }
  EXPECT_THROW(TransferFunction::from_points({0, 1}, {}, 8), UsageError);
}

TEST(TransferFunction, VersionsAndChangedEntries) {
  TransferFunction tf({0, 1}, 16);
  EXPECT_EQ(tf.version(), 0u);
  tf.set_entry(3, {1, 1, 1, 1});
  const auto v1 = tf.version();
  EXPECT_EQ(v1, 1u);
  std::vector<Rgba> two(2, Rgba{0.5f, 0, 0, 0.5f});
  tf.set_entries(10, two);
  EXPECT_EQ(tf.version(), 2u);

  ChangedEntries since0 = tf.changed_since(0);
  EXPECT_TRUE(since0.touches(3, 3));
  EXPECT_TRUE(since0.touches(0, 3));
  EXPECT_FALSE(since0.touches(4, 9));
  EXPECT_TRUE(since0.touches(9, 10));
  EXPECT_TRUE(since0.touches(11, 15));
  EXPECT_FALSE(since0.touches(12, 15));

  ChangedEntries since1 = tf.changed_since(v1);
  EXPECT_FALSE(since1.touches(0, 9));
  EXPECT_TRUE(since1.touches(10, 10));
  EXPECT_TRUE(tf.changed_since(tf.version()).none());

  EXPECT_TRUE(tf.touched_since(0, 3, 3));
  EXPECT_FALSE(tf.touched_since(v1, 3, 3));
  EXPECT_TRUE(tf.touched_since(v1, 0, 10));

  tf.set_domain({0, 2});
  EXPECT_TRUE(tf.changed_since(2).touches(5, 5));  // a domain change moves every entry
}

TEST(TransferFunction, ChangedSinceAVersionBeyondTheLogReportsEverything) {
  TransferFunction tf({0, 1}, 8);
  for (int k = 0; k < 10000; ++k) tf.set_entry(0, {0, 0, 0, float(k % 2)});
  EXPECT_TRUE(tf.changed_since(1).touches(7, 7));  // the log no longer reaches version 1
  EXPECT_TRUE(tf.touched_since(1, 7, 7));
  EXPECT_FALSE(tf.touched_since(tf.version() - 1, 1, 7));
}

// assign() takes another table as an edit: the version grows past both (a copy took the
// other's, lower, version: the player's fits after the first went unseen, issue 47 walk 5).
TEST(TransferFunction, AssignIsOneEditPastBothVersions) {
  TransferFunction a({0, 1}, 8);
  for (int k = 0; k < 5; ++k) a.set_entry(k, Rgba{1, 0, 0, 1});
  ASSERT_EQ(a.version(), 5u);
  const TransferFunction b({2, 3}, 4);  // version 0
  a.assign(b);
  EXPECT_EQ(a.version(), 6u);
  EXPECT_EQ(a.size(), 4);
  EXPECT_EQ(a.domain().lo, 2);
  EXPECT_EQ(a.entry(0).a, 0);
  // Everything changed since any earlier version; nothing since this one.
  EXPECT_TRUE(a.changed_since(5).touches(0, 0));
  EXPECT_TRUE(a.changed_since(5).touches(3, 3));
  EXPECT_TRUE(a.changed_since(0).touches(3, 3));
  EXPECT_TRUE(a.changed_since(6).none());
  EXPECT_TRUE(a.touched_since(5, 3, 3));
  // Against a table of a higher version, past that one.
  TransferFunction c({0, 1}, 4);
  for (int k = 0; k < 9; ++k) c.set_entry(0, Rgba{0, 0, 1, float(k) / 9});
  a.assign(c);
  EXPECT_EQ(a.version(), 10u);
}

TEST(TransferFunction, DiffEntriesComparesTables) {
  TransferFunction a({0, 1}, 8), b({0, 1}, 8);
  b.set_entry(2, {0, 0, 0, 0.1f});
  b.set_entry(5, {0, 1, 0, 0});
  ChangedEntries d = diff_entries(a, b);
  EXPECT_TRUE(d.touches(2, 2));
  EXPECT_FALSE(d.touches(3, 4));
  EXPECT_TRUE(d.touches(5, 7));
  EXPECT_FALSE(d.touches(6, 7));
  EXPECT_TRUE(diff_entries(a, TransferFunction({0, 2}, 8)).touches(4, 4));
  EXPECT_TRUE(diff_entries(a, a).none());
}

TEST(TransferFunction, TransparencyIsExactOverTheRange) {
  TransferFunction tf({0, 1}, 10);
  tf.set_entry(4, {1, 0, 0, 1e-6f});
  EXPECT_TRUE(tf.transparent(0, 3));
  EXPECT_FALSE(tf.transparent(0, 4));
  EXPECT_FALSE(tf.transparent(4, 9));
  EXPECT_TRUE(tf.transparent(5, 9));
  tf.set_entry(4, {1, 0, 0, 0});
  EXPECT_TRUE(tf.transparent(0, 9));
}

TEST(TransferFunction, OpacityCorrection) {
  // Spacing of one voxel leaves α alone; twice the spacing is LaMar's 1 − (1 − α)².
  EXPECT_FLOAT_EQ(corrected_opacity(0.3f, 1.0), 0.3f);
  EXPECT_FLOAT_EQ(corrected_opacity(0.3f, 2.0), 1 - 0.7f * 0.7f);
  EXPECT_FLOAT_EQ(corrected_opacity(0.19f, 0.5), 0.1f);  // √0.81 = 0.9
  EXPECT_FLOAT_EQ(corrected_opacity(0.0f, 0.5), 0.0f);
  EXPECT_FLOAT_EQ(corrected_opacity(1.0f, 0.5), 1.0f);
  // α outside [0, 1] is clamped first (what the renderer uploads).
  EXPECT_EQ(corrected_opacity(-0.1f, 2.0), 0.0f);
  EXPECT_EQ(corrected_opacity(1.5f, 2.0), 1.0f);
  EXPECT_TRUE(std::isnan(corrected_opacity(std::nanf(""), 2.0)));
  TransferFunction tf({0, 1}, 4);
  tf.set_entry(1, {0.2f, 0.4f, 0.6f, 0.5f});
  auto c = opacity_corrected(tf, 2.0);
  EXPECT_FLOAT_EQ(c[1].a, 0.75f);
  EXPECT_FLOAT_EQ(c[1].g, 0.4f);
  EXPECT_FLOAT_EQ(c[0].a, 0.0f);
}

}  // namespace
}  // namespace tsp
