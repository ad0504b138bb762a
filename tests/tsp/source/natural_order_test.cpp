#include "tsp/source/natural_order.h"

#include <gtest/gtest.h>

namespace tsp::io {
namespace {

TEST(NaturalOrder, DigitRunsCompareByValue) {
  std::vector<std::string> v = {"s10.raw", "s2.raw", "s1.raw", "s100.raw", "s09.raw"};
  natural_sort(v);
  EXPECT_EQ(v, (std::vector<std::string>{"s1.raw", "s2.raw", "s09.raw", "s10.raw", "s100.raw"}));
}

TEST(NaturalOrder, TextAndNumbersInterleave) {
  EXPECT_TRUE(natural_less("a2b10", "a2b11"));
  EXPECT_TRUE(natural_less("a2b9", "a2b10"));
  EXPECT_TRUE(natural_less("a", "a1"));
  EXPECT_TRUE(natural_less("a1", "b"));
  EXPECT_FALSE(natural_less("b", "a1"));
}

TEST(NaturalOrder, EqualValuesOrderByLeadingZerosAndIsStrictWeak) {
  EXPECT_TRUE(natural_less("7", "07"));
  EXPECT_FALSE(natural_less("07", "7"));
  EXPECT_FALSE(natural_less("x5", "x5"));
}

TEST(NaturalOrder, HugeNumbersDoNotOverflow) {
  EXPECT_TRUE(natural_less("t99999999999999999999999", "t100000000000000000000000"));
}

}  // namespace
}  // namespace tsp::io
