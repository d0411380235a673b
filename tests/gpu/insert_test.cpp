// insert on the embedded default: every listing matches the CPU replay exactly, and the validator
// fails on a broken result.
#include "support/test_support.hpp"

namespace oitbench::test {

class Insert : public GlTest {};

constexpr Resolution kSmall{32, 32};

TEST_F(Insert, EveryListingMatchesTheCpuReplay) {
  for (const char* variant : {"early-out", "no-early-out", "two-moves"})
    for (const char* keys : {"random", "front", "back"})
      for (const char* size : {"4", "13"}) {
        auto v = run_case("insert", {{"variant", variant}, {"keys", keys}, {"size", size}, {"repeat", "9"}}, kSmall);
        EXPECT_TRUE(v.valid) << variant << " keys=" << keys << " size=" << size << ": " << v.reason;
      }
}

TEST_F(Insert, ThirtyTwo) {
  for (const char* variant : {"early-out", "no-early-out", "two-moves"}) {
    auto v = run_case("insert", {{"variant", variant}, {"keys", "random"}, {"size", "32"}, {"repeat", "20"}}, kSmall);
    EXPECT_TRUE(v.valid) << variant << ": " << v.reason;
  }
}

TEST_F(Insert, LocalMemoryFormMatchesToo) {
  for (const char* variant : {"no-early-out", "two-moves"}) {
    auto v = run_case("insert", {{"variant", variant}, {"memory", "local"}, {"size", "12"}, {"repeat", "5"}}, kSmall);
    EXPECT_TRUE(v.valid) << variant << ": " << v.reason;
  }
}

// Mesa 22.3.6 llvmpipe loses the swaps of Listing 4.8's loop (break before the swap) when the
// array is dynamically indexed (memory=local); the register form is correct. The validator must
// report it; a driver that compiles it correctly passes.
TEST_F(Insert, EarlyOutLocalIsValidatedNotTrusted) {
  auto v = run_case("insert",
                    {{"variant", "early-out"}, {"memory", "local"}, {"keys", "back"}, {"size", "8"}, {"repeat", "1"}},
                    kSmall);
  if (!v.valid) RecordProperty("early_out_local_driver_bug", v.reason);
  EXPECT_TRUE(v.valid || gl().is_software_renderer()) << "early-out local invalid on a hardware driver: " << v.reason;
}

TEST_F(Insert, ValidatorCatchesAChangedPayload) {
  auto v =
      run_case("insert", {{"variant", "early-out"}, {"size", "8"}, {"repeat", "3"}, {"fault", "wrong-result"}}, kSmall);
  EXPECT_FALSE(v.valid);
  EXPECT_EQ(v.metrics.at("mismatched_pixels"), "1");
  EXPECT_NE(v.reason.find("pixel (1,1)[7]"), std::string::npos) << v.reason;
}

}  // namespace oitbench::test
