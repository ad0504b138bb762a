// The clip solid: parsing, signed distances against the shapes' formulas, CSG, and box
// classification against brute-force sampling (a box reported kept or removed must be so at every
// sample; across must hold samples of both sides unless conservative).
#include "tsp/clip/probe.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tsp/core/error.h"

namespace tsp {
namespace {

TEST(Probe, ParsesEveryKindAndRoundTrips) {
  const Probe plane = parse_probe("plane:0,0,2,1");
  EXPECT_EQ(plane.kind, Probe::Kind::plane);
  EXPECT_DOUBLE_EQ(plane.centre[2], 1.0);  // normalised
  EXPECT_DOUBLE_EQ(plane.radius, 0.5);
  const Probe sphere = parse_probe("sphere:1,2,3,4");
  EXPECT_EQ(sphere.kind, Probe::Kind::sphere);
  EXPECT_DOUBLE_EQ(sphere.radius, 4);
  const Probe box = parse_probe("box:1,2,3,4,5,6,10,20,30");
  EXPECT_EQ(box.size, (std::array<double, 3>{4, 5, 6}));
  EXPECT_EQ(box.angles, (std::array<double, 3>{10, 20, 30}));
  for (const Probe& p : {plane, sphere, box}) EXPECT_EQ(parse_probe(to_string(p)), p);
  for (const char* bad : {"plane:0,0,0,1", "sphere:1,2,3", "sphere:0,0,0,-1", "box:1,2,3,0,1,1",
                          "cone:1,2,3,4", "plane", "sphere:a,b,c,d", "sphere:1,2,3,nan"})
    EXPECT_THROW(parse_probe(bad), UsageError) << bad;
  EXPECT_EQ(parse_probe_op("union"), ProbeOp::unite);
  EXPECT_THROW(parse_probe_op("xor"), UsageError);
  std::vector<Probe> nine(9, sphere);
  EXPECT_THROW(ClipRegion(nine, ProbeOp::unite, {0, 0, 0}, {1, 1, 1}), UsageError);
}

TEST(Probe, DistancesFollowTheShapesAndTheGridGeometry) {
  const Probe sphere = parse_probe("sphere:10,0,0,3");
  const Probe box = parse_probe("box:0,0,0,1,2,3,0,0,90");  // rotated 90° about z: x ↔ y
  const ClipRegion s({sphere}, ProbeOp::intersect, {0, 0, 0}, {1, 1, 1});
  EXPECT_DOUBLE_EQ(s.distance({10, 0, 4}), 1.0);
  EXPECT_DOUBLE_EQ(s.distance({10, 0, 0}), -3.0);
  const ClipRegion b({box}, ProbeOp::intersect, {0, 0, 0}, {1, 1, 1});
  EXPECT_NEAR(b.distance({1.9, 0, 0}), -0.1, 1e-12);  // the 2-wide half size now along x
  EXPECT_NEAR(b.distance({0, 1.5, 0}), 0.5, 1e-12);   // the 1-wide along y
  EXPECT_NEAR(b.distance({0, 0, 4}), 1.0, 1e-12);
  // Sample coordinates map through origin and spacing: sample (5, 0, 0) at x = 1 + 2·5 = 11.
  const ClipRegion g({sphere}, ProbeOp::intersect, {1, 0, 0}, {2, 1, 1});
  EXPECT_TRUE(g.kept({5, 0, 0}));
  EXPECT_FALSE(g.kept({0, 0, 0}));
}

TEST(Probe, CsgKeepsTheRightPoints) {
  const Probe a = parse_probe("sphere:0,0,0,2"), b = parse_probe("sphere:2,0,0,2");
  const std::array<double, 3> only_a{-1, 0, 0}, both{1, 0, 0}, only_b{3, 0, 0}, none{9, 9, 9};
  auto kept = [&](ProbeOp op, const std::array<double, 3>& p) {
    return ClipRegion({a, b}, op, {0, 0, 0}, {1, 1, 1}).kept(p);
  };
  EXPECT_FALSE(kept(ProbeOp::intersect, only_a));
  EXPECT_TRUE(kept(ProbeOp::intersect, both));
  EXPECT_TRUE(kept(ProbeOp::unite, only_a));
  EXPECT_TRUE(kept(ProbeOp::unite, only_b));
  EXPECT_FALSE(kept(ProbeOp::unite, none));
  EXPECT_TRUE(kept(ProbeOp::subtract, only_a));
  EXPECT_FALSE(kept(ProbeOp::subtract, both));
  EXPECT_FALSE(kept(ProbeOp::subtract, only_b));
}

TEST(Probe, BoxClassificationAgreesWithSamplingEverywhere) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 40);
  const std::vector<std::vector<std::string>> cases = {
      {"plane:1,0.3,-0.2,20"},
      {"sphere:20,20,20,12"},
      {"box:20,18,22,10,6,8,20,35,-15"},
      {"sphere:15,20,20,10", "sphere:25,20,20,10"},
      {"box:20,20,20,15,15,15", "sphere:20,20,20,9"}};
  for (ProbeOp op : {ProbeOp::intersect, ProbeOp::unite, ProbeOp::subtract})
    for (const auto& texts : cases) {
      std::vector<Probe> probes;
      for (const auto& t : texts) probes.push_back(parse_probe(t));
      const ClipRegion clip(probes, op, {0, 0, 0}, {1, 1, 1});
      int across = 0, both_seen = 0;
      for (int trial = 0; trial < 300; ++trial) {
        Aabb box;
        for (int a = 0; a < 3; ++a) {
          const double x = u(rng), y = u(rng);
          box.lo[a] = std::min(x, y);
          box.hi[a] = std::max(x, y);
        }
        const ClipSide side = clip.classify(box);
        bool any_kept = false, any_removed = false;
        for (int i = 0; i <= 6; ++i)
          for (int j = 0; j <= 6; ++j)
            for (int k = 0; k <= 6; ++k) {
              const std::array<double, 3> p{box.lo[0] + (box.hi[0] - box.lo[0]) * i / 6,
                                            box.lo[1] + (box.hi[1] - box.lo[1]) * j / 6,
                                            box.lo[2] + (box.hi[2] - box.lo[2]) * k / 6};
              (clip.kept(p) ? any_kept : any_removed) = true;
            }
        if (side == ClipSide::kept) EXPECT_FALSE(any_removed) << texts[0] << " " << to_string(op);
        if (side == ClipSide::removed) EXPECT_FALSE(any_kept) << texts[0] << " " << to_string(op);
        if (side == ClipSide::straddles) {
          ++across;
          both_seen += any_kept && any_removed;
        }
      }
      // Conservative, but not wildly: most boxes reported across do hold both sides.
      if (across > 0) EXPECT_GT(double(both_seen) / across, 0.5) << texts[0] << " " << to_string(op);
    }
}

// The solid's bound against sampling: every kept sample of the domain lies inside it, and for a
// single probe it is tight (kept samples within two grid steps of each of its faces); an
// axis-aligned plane bounds exactly its half, and a solid missing the domain bounds nothing.
TEST(Probe, BoundHoldsEveryKeptSampleAndIsTightForOneProbe) {
  const Aabb domain{{0, 0, 0}, {40, 30, 20}};
  const std::array<double, 3> origin{-3, 2, 5}, spacing{0.5, 2, 1.5};
  const std::vector<std::pair<std::vector<std::string>, ProbeOp>> cases = {
      {{"plane:1,0.4,-0.3,2"}, ProbeOp::intersect},
      {{"sphere:5,30,20,9"}, ProbeOp::intersect},
      {{"box:6,40,18,6,10,4,20,35,10"}, ProbeOp::intersect},
      {{"plane:1,0,0,4", "sphere:5,30,20,12"}, ProbeOp::intersect},
      {{"sphere:0,10,10,5", "sphere:12,50,30,6"}, ProbeOp::unite},
      {{"box:6,30,18,10,20,8", "sphere:6,30,18,5"}, ProbeOp::subtract},
  };
  for (const auto& [texts, op] : cases) {
    std::vector<Probe> probes;
    for (const std::string& t : texts) probes.push_back(parse_probe(t));
    const ClipRegion clip(probes, op, origin, spacing);
    const Aabb b = clip.bound(domain);
    Aabb seen{{1e300, 1e300, 1e300}, {-1e300, -1e300, -1e300}};
    const double step = 0.25;
    for (double x = domain.lo[0]; x <= domain.hi[0]; x += step)
      for (double y = domain.lo[1]; y <= domain.hi[1]; y += step)
        for (double z = domain.lo[2]; z <= domain.hi[2]; z += step) {
          if (!clip.kept({x, y, z})) continue;
          const std::array<double, 3> q{x, y, z};
          for (int a = 0; a < 3; ++a) {
            ASSERT_GE(q[a], b.lo[a]) << texts[0] << " axis " << a;
            ASSERT_LE(q[a], b.hi[a]) << texts[0] << " axis " << a;
            seen.lo[a] = std::min(seen.lo[a], q[a]);
            seen.hi[a] = std::max(seen.hi[a], q[a]);
          }
        }
    if (texts.size() == 1)
      for (int a = 0; a < 3; ++a) {
        EXPECT_LT(seen.lo[a] - b.lo[a], 2 * step) << texts[0] << " axis " << a;
        EXPECT_LT(b.hi[a] - seen.hi[a], 2 * step) << texts[0] << " axis " << a;
      }
  }
  // x ≤ 7 in physical units: sample x ≤ (7 + 3) / 0.5 = 20, the other axes whole.
  const Aabb half = ClipRegion({parse_probe("plane:1,0,0,7")}, ProbeOp::intersect, origin, spacing)
                        .bound(domain);
  EXPECT_NEAR(half.hi[0], 20, 1e-6);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(half.lo[a], 0, 1e-6);
  EXPECT_NEAR(half.hi[1], 30, 1e-6);
  EXPECT_NEAR(half.hi[2], 20, 1e-6);
  const Aabb none = ClipRegion({parse_probe("sphere:500,500,500,1")}, ProbeOp::intersect, origin,
                               spacing)
                        .bound(domain);
  EXPECT_GT(none.lo[0], none.hi[0]);
  EXPECT_EQ(ClipRegion().bound(domain), domain);
}

}  // namespace
}  // namespace tsp
