// lines: the per-fragment exact resolve matches the CPU reference, the per-primitive radix sort
// matches a stable CPU sort exactly, and both validators fail on a broken variant.
#include "support/test_support.hpp"

namespace oitbench::test {

class Lines : public GlTest {};

TEST_F(Lines, ExactAndSlicesAreValidAndSlicesCostSomeError) {
  auto exact = run_case("lines", {{"technique", "exact"}, {"segments", "6000"}}, {96, 96});
  EXPECT_TRUE(exact.valid) << exact.reason;
  EXPECT_LT(std::stod(exact.metrics.at("max_abs_error")), 2.0 / 255);
  for (const char* slices : {"256", "4"}) {
    auto v = run_case("lines", {{"technique", "slices"}, {"segments", "6000"}, {"slices", slices}}, {96, 96});
    EXPECT_TRUE(v.valid) << v.reason;
    EXPECT_GT(std::stod(v.metrics.at("rmse")), 0.0) << "slices are an approximation";
  }
  // Fewer slices sort coarser: more error (the same segments, same order within a slice).
  auto coarse = run_case("lines", {{"technique", "slices"}, {"segments", "6000"}, {"slices", "2"}}, {96, 96});
  auto fine = run_case("lines", {{"technique", "slices"}, {"segments", "6000"}, {"slices", "1024"}}, {96, 96});
  EXPECT_GT(std::stod(coarse.metrics.at("rmse")), std::stod(fine.metrics.at("rmse")));
}

TEST_F(Lines, ValidatorsCatchABrokenSortAndABrokenResolve) {
  auto s = run_case("lines", {{"technique", "slices"}, {"segments", "3000"}, {"fault", "wrong-result"}}, {64, 64});
  EXPECT_FALSE(s.valid);
  EXPECT_NE(s.reason.find("radix sort differs"), std::string::npos) << s.reason;
  auto e = run_case("lines", {{"technique", "exact"}, {"segments", "3000"}, {"fault", "wrong-result"}}, {64, 64});
  EXPECT_FALSE(e.valid);
}

}  // namespace oitbench::test
