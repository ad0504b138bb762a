// Table 4's tolerance search against analytic error curves: the bisection's invariant, the
// brackets, the cases where nothing or everything meets the target, shared evaluations, and the
// error span of a metric.
#include "jobs/tolerance_search.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <stdexcept>

namespace {

using tspgl::ErrorSpan;
using tspgl::FoundTolerance;
using tspgl::search_tolerances;

// ΔE grows with log(tol) from 0.5 at and below 1e-3 to 5.5 at 1: ΔE(tol) = 0.5 + 5·(1 + log10(tol)/3).
double log_curve(double tol) {
  if (tol <= 1e-3) return 0.5;
  return 0.5 + 5.0 * (1.0 + std::log10(tol) / 3.0);
}

TEST(ToleranceSearch, BisectionConvergesOnTheCrossingFromBelow) {
  std::map<double, int> calls;
  auto at = [&](double tol) {
    ++calls[tol];
    return log_curve(tol);
  };
  const ErrorSpan span{1e-3, 1.0};
  const auto found = search_tolerances(at, span, {1.0, 3.0}, 30);
  ASSERT_EQ(found.size(), 2u);
  for (const FoundTolerance& f : found) {
    // Exact crossing: 0.5 + 5(1 + log10(t)/3) = target.
    const double exact = std::pow(10.0, 3.0 * ((f.target - 0.5) / 5.0 - 1.0));
    EXPECT_LE(f.tol, exact * (1 + 1e-9)) << f.target;   // lo always meets the target
    EXPECT_NEAR(std::log10(f.tol), std::log10(exact), 1e-6) << f.target;
    EXPECT_TRUE(f.met);
    EXPECT_LE(f.mean_de, f.target);
    EXPECT_DOUBLE_EQ(f.mean_de, log_curve(f.tol));
  }
  EXPECT_LT(found[0].tol, found[1].tol);  // a looser target allows a larger tolerance
  // Zero is evaluated first, and no tolerance twice.
  EXPECT_EQ(calls.begin()->first, 0.0);
  for (auto [tol, n] : calls) EXPECT_EQ(n, 1) << tol;
}

TEST(ToleranceSearch, CoarsestPictureWithinTheTargetTakesTheLargestError) {
  const auto found = search_tolerances([](double) { return 0.2; }, ErrorSpan{1e-4, 0.7}, {1.0}, 10);
  EXPECT_DOUBLE_EQ(found[0].tol, 0.7);
  EXPECT_TRUE(found[0].met);
}

TEST(ToleranceSearch, TargetMissedEvenAtTheLowBracketGivesZero) {
  // Zero tolerance is within 0.4; every positive tolerance is at 9.
  auto at = [](double tol) { return tol == 0 ? 0.4 : 9.0; };
  const auto found = search_tolerances(at, ErrorSpan{1e-3, 1}, {1.0, 0.1}, 10);
  EXPECT_EQ(found[0].tol, 0);
  EXPECT_DOUBLE_EQ(found[0].mean_de, 0.4);
  EXPECT_TRUE(found[0].met);
  EXPECT_EQ(found[1].tol, 0);
  EXPECT_FALSE(found[1].met);  // not even zero tolerance meets ΔE 0.1
}

TEST(ToleranceSearch, NoPositiveErrorMeansZeroTolerance) {
  int calls = 0;
  const auto found = search_tolerances(
      [&](double) {
        ++calls;
        return 0.0;
      },
      ErrorSpan{0, 0}, {1.0, 3.0}, 10);
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(found[0].tol, 0);
  EXPECT_TRUE(found[1].met);
}

TEST(ToleranceSearch, LowBracketIsBoundedToNineDecades) {
  double lowest = 1;
  auto at = [&](double tol) {
    if (tol > 0) lowest = std::min(lowest, tol);
    return tol < 1e-5 ? 0.5 : 2.0;
  };
  search_tolerances(at, ErrorSpan{1e-30, 1.0}, {1.0}, 4);
  EXPECT_DOUBLE_EQ(lowest, std::pow(10.0, -tspgl::kMaxSearchDecades));
}

TEST(ToleranceSearch, ErrorsOfTheCallbackPassThrough) {
  EXPECT_THROW(search_tolerances([](double) -> double { throw std::runtime_error("gl"); },
                                 ErrorSpan{1e-3, 1}, {1.0}, 3),
               std::runtime_error);
}

TEST(ToleranceSearch, ErrorSpanSkipsTransparentAndNonFiniteNodes) {
  tsp::MetricResult m;
  m.errors.spatial = {0.0f, 0.5f, 9.0f, NAN, 0.02f};
  m.errors.temporal = {0.0f, 0.01f, 8.0f, 0.3f, INFINITY};
  m.transparent = {0, 0, 1, 0, 0};
  const ErrorSpan s = tspgl::error_span(m);
  EXPECT_DOUBLE_EQ(s.largest, 0.5);
  EXPECT_FLOAT_EQ(float(s.smallest_positive), 0.01f);
  tsp::MetricResult zero;
  zero.errors.spatial = {0.0f};
  zero.errors.temporal = {0.0f};
  zero.transparent = {0};
  EXPECT_EQ(tspgl::error_span(zero).smallest_positive, 0);
  EXPECT_EQ(tspgl::error_span(zero).largest, 0);
}

}  // namespace
