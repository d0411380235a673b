#include "core/stats.hpp"

#include <gtest/gtest.h>

namespace oitbench {

TEST(Stats, OddCount) {
  auto s = summarize({5, 1, 3});
  EXPECT_EQ(s.n, 3u);
  EXPECT_DOUBLE_EQ(s.median, 3);
  EXPECT_DOUBLE_EQ(s.mad, 2);  // deviations 2, 2, 0
  EXPECT_DOUBLE_EQ(s.min, 1);
  EXPECT_DOUBLE_EQ(s.max, 5);
  EXPECT_DOUBLE_EQ(s.mean, 3);
  EXPECT_DOUBLE_EQ(s.stddev, 2);
}

TEST(Stats, EvenCountTakesTheMeanOfTheMiddlePair) {
  auto s = summarize({4, 1, 3, 2});
  EXPECT_DOUBLE_EQ(s.median, 2.5);
  EXPECT_DOUBLE_EQ(s.mad, 1.0);  // deviations 1.5, 0.5, 0.5, 1.5
  EXPECT_NEAR(s.stddev, 1.2909944, 1e-6);
}

TEST(Stats, TiesAndOneSample) {
  auto t = summarize({7, 7, 7, 7});
  EXPECT_DOUBLE_EQ(t.median, 7);
  EXPECT_DOUBLE_EQ(t.mad, 0);
  EXPECT_DOUBLE_EQ(t.stddev, 0);
  EXPECT_EQ(t.outliers, 0u);
  auto one = summarize({42});
  EXPECT_EQ(one.n, 1u);
  EXPECT_DOUBLE_EQ(one.median, 42);
  EXPECT_DOUBLE_EQ(one.mad, 0);
  EXPECT_DOUBLE_EQ(one.stddev, 0);
}

TEST(Stats, OutliersBeyondFiveMads) {
  auto s = summarize({10, 11, 9, 10, 10.5, 9.5, 100});
  EXPECT_EQ(s.outliers, 1u);
  EXPECT_DOUBLE_EQ(s.median, 10);
}

TEST(Stats, EmptyIsAnErrorForMedian) {
  EXPECT_THROW(median_of({}), std::invalid_argument);
  EXPECT_EQ(summarize({}).n, 0u);
}

}  // namespace oitbench
