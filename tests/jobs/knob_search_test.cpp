// The knob search on analytic probes (no GL): the error and the time of a configuration are
// formulas, so the right answer is known exactly.
#include "jobs/knob_search.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "tsp/core/error.h"

namespace tspgl {
namespace {

// Error grows with spacing and tolerance; time falls with both; rays are 2× faster than slices.
ProbeResult analytic(const Knobs& k) {
  const double de = 0.4 * k.spacing + (k.baseline ? 0 : 100 * k.tol);
  const double ms = (k.compositing == Compositing::rays ? 10 : 20) / k.spacing / (1 + 10 * k.tol);
  return {de, ms};
}

TEST(KnobSearch, BaselineKeepsEveryConfigurationWithinTheTargetFastestFirst) {
  KnobGrid g{{Compositing::slices, Compositing::rays}, {0.5, 1, 2, 4}};
  int calls = 0;
  const auto found = search_baseline_knobs(
      [&](const Knobs& k) {
        ++calls;
        EXPECT_TRUE(k.baseline);
        return analytic(k);
      },
      g, {1.0, 3.0});
  EXPECT_EQ(calls, 8);  // each configuration once, shared by the targets
  ASSERT_EQ(found.size(), 2u);
  // ΔE ≤ 1: spacings 0.5, 1 (0.2, 0.4); 2 gives 0.8 too; 4 gives 1.6.
  ASSERT_EQ(found[0].size(), 6u);
  EXPECT_EQ(found[0][0].knobs.compositing, Compositing::rays);
  EXPECT_EQ(found[0][0].knobs.spacing, 2);
  for (std::size_t i = 1; i < found[0].size(); ++i)
    EXPECT_LE(found[0][i - 1].probe.ms, found[0][i].probe.ms);
  ASSERT_EQ(found[1].size(), 8u);
  EXPECT_EQ(found[1][0].knobs.spacing, 4);
}

TEST(KnobSearch, TspFindsTheLargestTolerancePerSpacing) {
  KnobGrid g{{Compositing::rays}, {1, 2}};
  const ErrorSpan span{1e-6, 1.0};
  const auto found = search_tsp_knobs(analytic, g, span, {1.0}, 30);
  ASSERT_EQ(found.size(), 1u);
  ASSERT_EQ(found[0].size(), 2u);
  for (const KnobCandidate& c : found[0]) {
    EXPECT_FALSE(c.knobs.baseline);
    // 0.4·s + 100·tol = 1 at the boundary: tol = (1 − 0.4 s)/100, approached from below.
    const double want = (1 - 0.4 * c.knobs.spacing) / 100;
    EXPECT_LE(c.knobs.tol, want);
    EXPECT_NEAR(c.knobs.tol, want, want * 1e-3);
    EXPECT_LE(c.probe.mean_de, 1.0);
    EXPECT_DOUBLE_EQ(c.probe.mean_de, analytic(c.knobs).mean_de);  // the probe of that tolerance
  }
  EXPECT_LE(found[0][0].probe.ms, found[0][1].probe.ms);
}

// When a tolerance costs time (flat nodes break a whole-volume frame into the brick grid), the
// fastest tolerance within the target wins — here zero tolerance, probed first.
TEST(KnobSearch, TspPrefersAFasterSmallerToleranceIncludingZero) {
  KnobGrid g{{Compositing::rays}, {1}};
  const ProbeKnobs slower_with_tol = [](const Knobs& k) {
    return ProbeResult{0.4 * k.spacing + 100 * k.tol, 10.0 + (k.tol > 0 ? 5.0 : 0.0)};
  };
  const auto found = search_tsp_knobs(slower_with_tol, g, ErrorSpan{1e-6, 1.0}, {1.0}, 20);
  ASSERT_EQ(found[0].size(), 1u);
  EXPECT_EQ(found[0][0].knobs.tol, 0.0);
  EXPECT_DOUBLE_EQ(found[0][0].probe.ms, 10.0);
}

// LOD levels are a TSP knob: the TSP grid holds every level × compositing × spacing, the
// baseline's only full resolution, and the render options name the level.
TEST(KnobSearch, LodLevelsAreATspKnobNamedInTheRenderOptions) {
  KnobGrid g{{Compositing::rays}, {1, 2}};
  g.lod_levels = {0, 1, 2};
  EXPECT_EQ(grid_cells(g, false).size(), 6u);
  EXPECT_EQ(grid_cells(g, true).size(), 2u);
  for (const Knobs& k : grid_cells(g, true)) EXPECT_EQ(k.lod_level, 0);
  Knobs k;
  k.lod_level = 2;
  EXPECT_NE(render_options(k, tsp::Metric::approximate).find(" --lod 2"), std::string::npos);
  k.lod_level = 0;
  EXPECT_EQ(render_options(k, tsp::Metric::approximate).find("--lod"), std::string::npos);
}

// Tolerance rules: each is a TSP cell of its own, named exactly in the render options; zero
// tolerance (the same picture under every rule) is probed once per cell and offered once; a rule
// whose tolerance costs less error wins where it reaches further.
TEST(KnobSearch, ToleranceRulesAreSearchedAndNamedApart) {
  KnobGrid g{{Compositing::rays}, {1}};
  g.tolerance_rules = {ToleranceRule::equal, ToleranceRule::temporal};
  ASSERT_EQ(grid_cells(g, false).size(), 2u);
  EXPECT_EQ(grid_cells(g, true).size(), 1u);
  int zero_probes = 0;
  // Under the temporal rule a tolerance costs a tenth of the error (spatial error is what hurts).
  auto probe = [&](const Knobs& k) {
    if (k.tol == 0) ++zero_probes;
    const double weight = k.rule == ToleranceRule::temporal ? 10 : 100;
    return ProbeResult{0.4 * k.spacing + weight * k.tol, 10 / k.spacing / (1 + 10 * k.tol)};
  };
  const auto found = search_tsp_knobs(probe, g, ErrorSpan{1e-6, 1.0}, {1.0}, 30);
  EXPECT_EQ(zero_probes, 1);
  ASSERT_EQ(found[0].size(), 2u);
  const Knobs& best = found[0][0].knobs;
  EXPECT_EQ(best.rule, ToleranceRule::temporal);
  EXPECT_NEAR(best.tol, 0.06, 1e-3);  // 0.4 + 10·τ = 1
  EXPECT_NEAR(found[0][1].knobs.tol, 0.006, 1e-4);
  EXPECT_EQ(found[0][1].knobs.rule, ToleranceRule::equal);
  const struct {
    ToleranceRule rule;
    double spatial, temporal;
    const char* options;
  } rules[] = {{ToleranceRule::temporal, 0, 0.5, "--spatial-tol 0 --temporal-tol 0.5"},
               {ToleranceRule::spatial, 0.5, 0, "--spatial-tol 0.5 --temporal-tol 0"}};
  for (const auto& r : rules) {
    RenderSettings s;
    Knobs k;
    k.tol = 0.5;
    k.rule = r.rule;
    apply(k, s);
    EXPECT_EQ(s.tol.spatial, r.spatial);
    EXPECT_EQ(s.tol.temporal, r.temporal);
    EXPECT_NE(render_options(k, tsp::Metric::approximate).find(r.options), std::string::npos);
  }
  EXPECT_EQ(parse_tolerance_rule("temporal", "--x"), ToleranceRule::temporal);
  EXPECT_THROW(parse_tolerance_rule("both", "--x"), tsp::UsageError);
}

TEST(KnobSearch, ConfigurationsThatMissEveryTargetAreLeftOut) {
  KnobGrid g{{Compositing::slices}, {4}};  // ΔE 1.6 even at zero tolerance
  EXPECT_TRUE(search_tsp_knobs(analytic, g, ErrorSpan{1e-6, 1.0}, {1.0}, 10)[0].empty());
  EXPECT_TRUE(search_baseline_knobs(analytic, g, {1.0})[0].empty());
}

TEST(KnobSearch, RenderOptionsNameEveryKnobExactly) {
  Knobs k;
  k.compositing = Compositing::boxes;
  k.spacing = 1.5;
  k.tol = 0.1;
  const std::string s = render_options(k, tsp::Metric::perceptual);
  EXPECT_EQ(s,
            "--compositing boxes --spacing 1.5 --metric perceptual --spatial-tol "
            "0.10000000000000001 --temporal-tol 0.10000000000000001");
  EXPECT_EQ(std::strtod("0.10000000000000001", nullptr), 0.1);
  k.baseline = true;
  EXPECT_EQ(render_options(k, tsp::Metric::perceptual), "--baseline --compositing boxes --spacing 1.5");
}

}  // namespace
}  // namespace tspgl
