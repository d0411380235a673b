// The one check behind every numeric option: nan, inf, text and out-of-bounds values refused with
// readable bounds; whole numbers rewritten as digits.
#include "app/number_option.hpp"

#include <gtest/gtest.h>

namespace oitbench::app {
namespace {

TEST(NumberOption, RefusesNanInfTextAndValuesOutsideWithReadableBounds) {
  const NumberBounds seconds{0, 604800, true, false, false, "seconds"};
  for (std::string bad : {"nan", "NaN", "inf", "-inf", "0", "-1", "1e300", "604800.5", "abc", "", " 1", "1x"}) {
    std::string text = bad;
    EXPECT_EQ(check_number(text, seconds), "must be a number in (0, 604800] seconds, got '" + bad + "'") << bad;
  }
  for (std::string good : {"1e-9", "0.5", "604800", "+3"}) {
    std::string text = good;
    EXPECT_EQ(check_number(text, seconds), "") << good;
    EXPECT_EQ(text, good) << "a real number is left as written";
  }
}

TEST(NumberOption, WholeNumbersAreWholeAndRewrittenAsDigits) {
  const NumberBounds reps{1, 100000, false, false, true, ""};
  std::string text = "1e3";
  EXPECT_EQ(check_number(text, reps), "");
  EXPECT_EQ(text, "1000");
  for (std::string bad : {"1.5", "0", "100001", "nan", "1e300", "-0"}) {
    std::string t = bad;
    EXPECT_EQ(check_number(t, reps), "must be a whole number in [1, 100000], got '" + bad + "'") << bad;
  }
  EXPECT_EQ(describe({0, 1, true, false, false, ""}), "a number in (0, 1]");
  EXPECT_EQ(describe({0, 1, false, true, false, "%"}), "a number in [0, 1) %");
}

}  // namespace
}  // namespace oitbench::app
