// core::median: the middle value of an odd count, the mean of the middle two of an even one, in
// any input order; NaN for no values.
#include "core/median.h"

#include <gtest/gtest.h>

#include <cmath>

using crashlink::core::median;

TEST(Median, OddCountTakesTheMiddleValueInAnyOrder) {
  EXPECT_EQ(median({3.0, 1.0, 2.0}), 2.0);
  EXPECT_EQ(median({5.0}), 5.0);
  EXPECT_EQ(median({9.0, -1.0, 4.0, 4.0, 0.5}), 4.0);
}

TEST(Median, EvenCountTakesTheMeanOfTheMiddleTwo) {
  EXPECT_EQ(median({4.0, 1.0, 3.0, 2.0}), 2.5);
  EXPECT_EQ(median({1.0, 2.0}), 1.5);
}

TEST(Median, NoValuesGiveNaN) {
  EXPECT_TRUE(std::isnan(median({})));
}
