// stencil on the embedded default: masked and unmasked resolves give the CPU reference's image,
// pixels outside the coverage stay untouched, and the validator can fail.
#include "support/test_support.hpp"

namespace oitbench::test {

class Stencil : public GlTest {};

TEST_F(Stencil, BothVariantsMatchTheCpuReference) {
  for (const char* variant : {"no-stencil", "stencil"})
    for (const char* resolve : {"blend", "sort"})
      for (const char* coverage : {"1", "37", "100"}) {
        auto v = run_case(
            "stencil",
            {{"variant", variant}, {"resolve", resolve}, {"coverage", coverage}, {"nodes", "8"}, {"layers", "5"}});
        EXPECT_TRUE(v.valid) << variant << " " << resolve << " coverage " << coverage << ": " << v.reason;
      }
}

TEST_F(Stencil, ValidatorCatchesAWrongPixelInsideAndOutside) {
  // The fault perturbs pixel (1,0) (inside) and the top-right pixel (outside at 10 % coverage).
  auto unmasked = run_case("stencil", {{"variant", "no-stencil"}, {"coverage", "10"}, {"fault", "wrong-result"}});
  EXPECT_FALSE(unmasked.valid);
  EXPECT_EQ(unmasked.metrics.at("mismatched_pixels"), "2");
  EXPECT_EQ(unmasked.metrics.at("touched_outside"), "1");
  EXPECT_NE(unmasked.reason.find("pixel (1,0)"), std::string::npos) << unmasked.reason;
  // With the mask the resolve never runs outside the coverage: only the inside pixel is wrong.
  auto masked = run_case("stencil", {{"variant", "stencil"}, {"coverage", "10"}, {"fault", "wrong-result"}});
  EXPECT_FALSE(masked.valid);
  EXPECT_EQ(masked.metrics.at("mismatched_pixels"), "1");
  EXPECT_EQ(masked.metrics.at("touched_outside"), "0");
}

}  // namespace oitbench::test
