#include "tsp/tree/time_tree.h"

#include <gtest/gtest.h>

#include <set>

namespace tsp {
namespace {

// Independent recursive construction of the spans the spec prescribes.
void expected_spans(int t1, int t2, std::multiset<std::pair<int, int>>& out) {
  out.insert({t1, t2});
  if (t1 == t2) return;
  int mid = (t1 + t2) / 2;
  expected_spans(t1, mid, out);
  expected_spans(mid + 1, t2, out);
}

TEST(TimeTree, SpansMatchRecursiveDefinitionForManySizes) {
  for (int T = 1; T <= 40; ++T) {
    TimeTree tree(T);
    ASSERT_EQ(tree.size(), 2 * T - 1);
    std::multiset<std::pair<int, int>> want, got;
    expected_spans(0, T - 1, want);
    for (int i = 0; i < tree.size(); ++i) got.insert({tree.span(i).t0, tree.span(i).t1});
    EXPECT_EQ(got, want) << "T=" << T;
    EXPECT_EQ(tree.span(0), (Span{0, T - 1}));
  }
}

TEST(TimeTree, ChildrenSplitAtFloorMidpointAndLeavesAreSingleSteps) {
  TimeTree tree(13);
  for (int i = 0; i < tree.size(); ++i) {
    Span s = tree.span(i);
    if (tree.is_leaf(i)) {
      EXPECT_EQ(s.t0, s.t1);
      EXPECT_EQ(tree.leaf_of(s.t0), i);
      continue;
    }
    int mid = (s.t0 + s.t1) / 2;
    EXPECT_EQ(tree.span(tree.left(i)), (Span{s.t0, mid}));
    EXPECT_EQ(tree.span(tree.right(i)), (Span{mid + 1, s.t1}));
    EXPECT_EQ(tree.parent(tree.left(i)), i);
    EXPECT_EQ(tree.level(tree.left(i)), tree.level(i) + 1);
  }
}

TEST(TimeTree, ChildHoldingWalksToTheLeafOfEveryStep) {
  TimeTree tree(21);
  for (int t = 0; t < 21; ++t) {
    int id = 0;
    int hops = 0;
    while (!tree.is_leaf(id)) {
      id = tree.child_holding(id, t);
      ASSERT_TRUE(tree.span(id).contains(t));
      ++hops;
    }
    EXPECT_EQ(id, tree.leaf_of(t));
    EXPECT_LE(hops, tree.depth());
  }
}

}  // namespace
}  // namespace tsp
