// The bench's search sample: every step when few, else evenly spread with both ends.
#include "jobs/bench_job.h"
#include "jobs/tolerance_search.h"

#include <gtest/gtest.h>

#include "tsp/core/error.h"

namespace {

TEST(BenchJob, SearchSampleTakesEveryStepWhenFew) {
  EXPECT_EQ(tspgl::search_step_sample(2, 5, 8), (std::vector<int>{2, 3, 4, 5}));
  EXPECT_EQ(tspgl::search_step_sample(3, 3, 8), (std::vector<int>{3}));
}

TEST(BenchJob, SearchSampleSpreadsEvenlyWithBothEnds) {
  EXPECT_EQ(tspgl::search_step_sample(0, 31, 4), (std::vector<int>{0, 10, 21, 31}));
  EXPECT_EQ(tspgl::search_step_sample(10, 20, 3), (std::vector<int>{10, 15, 20}));
  EXPECT_EQ(tspgl::search_step_sample(0, 9, 1), (std::vector<int>{0}));
}

TEST(BenchJob, SearchSampleIsEmptyForNothing) {
  EXPECT_TRUE(tspgl::search_step_sample(0, 9, 0).empty());
  EXPECT_TRUE(tspgl::search_step_sample(5, 4, 3).empty());
}

TEST(BenchJob, BadOptionsAreUsageErrors) {
  tspgl::BenchOptions o;
  EXPECT_THROW(tspgl::run_bench(o), tsp::UsageError);  // no output directory
  o.out_dir = "/nonexistent-never";
  o.targets = {0};
  EXPECT_THROW(tspgl::run_bench(o), tsp::UsageError);
  o.targets = {1};
  o.metrics.clear();
  EXPECT_THROW(tspgl::run_bench(o), tsp::UsageError);
}

}  // namespace
