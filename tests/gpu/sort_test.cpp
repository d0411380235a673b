// sort on the embedded default: every algorithm sorts (keys in order, the same (key, payload)
// multiset), duplicates included, and the validator fails on a broken result.
#include <string>

#include "support/test_support.hpp"

namespace oitbench::test {

class Sort : public GlTest {};

// 32x32 pixels; llvmpipe's JIT of each shader (0.3-8 s), not the sorting, is what these tests wait for.
constexpr Resolution kSmall{32, 32};

const char* const kAlgorithms[] = {
    "insertion-naive", "insertion-v1", "insertion-v2", "bubble",         "bubble-early", "shell-offset",
    "shell-register",  "merge",        "bitonic",      "odd-even-merge", "rbs"};

TEST_F(Sort, EveryAlgorithmSortsInItsMemoryForms) {
  for (const char* variant : kAlgorithms)
    for (const char* memory : {"local", "registers"}) {
      if ((std::string(variant) == "merge" && std::string(memory) == "registers") ||
          (std::string(variant) == "rbs" && std::string(memory) == "local"))
        continue;  // the forms that do not exist (see ImpossibleFormsAreUnsupportedWithAReason)
      // n=13: not a power of two (the networks drop comparators past the end), with tied keys.
      for (const char* n : {"4", "13"}) {
        const char* keys = std::string(n) == "13" ? "duplicates" : "random";
        auto v = run_case("sort", {{"variant", variant}, {"memory", memory}, {"n", n}, {"keys", keys}}, kSmall);
        EXPECT_TRUE(v.valid) << variant << " memory=" << memory << " n=" << n << " keys=" << keys << ": " << v.reason;
      }
    }
}

// A 32-element shader takes 0.6-8 s to JIT on llvmpipe without the disk cache, and rbs's nest of
// 31 ifs takes minutes (204 s measured), so n=32 is checked for insertion v2 and the bitonic
// network's full power of two; rbs is checked up to n=16 (below).
TEST_F(Sort, ThirtyTwoElements) {
  for (const char* variant : {"insertion-v2", "bitonic"}) {
    auto v = run_case("sort", {{"variant", variant}, {"memory", "registers"}, {"n", "32"}, {"keys", "few-distinct"}},
                      kSmall);
    EXPECT_TRUE(v.valid) << variant << ": " << v.reason;
  }
}

TEST_F(Sort, RbsSixteen) {
  for (const char* keys : {"sorted", "reverse", "duplicates"}) {
    auto v = run_case("sort", {{"variant", "rbs"}, {"memory", "registers"}, {"n", "16"}, {"keys", keys}}, kSmall);
    EXPECT_TRUE(v.valid) << keys << ": " << v.reason;
  }
}

// The unrolled register networks (sorts/network.glsl): both compare-exchange forms, a power of two
// and sizes that are not (comparators past the end dropped), every key distribution, both stages.
TEST_F(Sort, RegisterNetworksSort) {
  for (const char* variant : {"bitonic-network", "odd-even-merge-network"}) {
    for (const char* compare : {"min-max", "select"})
      for (const char* n : {"2", "13", "16"}) {
        auto v = run_case(
            "sort",
            {{"variant", variant}, {"memory", "registers"}, {"n", n}, {"keys", "duplicates"}, {"compare", compare}},
            kSmall);
        EXPECT_TRUE(v.valid) << variant << " compare=" << compare << " n=" << n << ": " << v.reason;
      }
    for (const char* keys : {"sorted", "reverse", "few-distinct"}) {
      auto v = run_case("sort", {{"variant", variant}, {"memory", "registers"}, {"n", "8"}, {"keys", keys}}, kSmall);
      EXPECT_TRUE(v.valid) << variant << " keys=" << keys << ": " << v.reason;
    }
    auto v =
        run_case("sort", {{"variant", variant}, {"memory", "registers"}, {"n", "32"}, {"stage", "compute"}}, kSmall);
    EXPECT_TRUE(v.valid) << variant << " n=32 compute: " << v.reason;
  }
}

TEST_F(Sort, ValidatorCatchesABrokenNetwork) {
  for (const char* variant : {"bitonic-network", "odd-even-merge-network"}) {
    auto v = run_case("sort", {{"variant", variant}, {"memory", "registers"}, {"n", "8"}, {"fault", "wrong-result"}},
                      kSmall);
    EXPECT_FALSE(v.valid) << variant;
    EXPECT_EQ(v.metrics.at("unsorted_pixels"), "1") << variant << ": " << v.reason;
    EXPECT_EQ(v.metrics.at("changed_pixels"), "1") << variant << ": " << v.reason;
  }
}

TEST_F(Sort, KeyDistributionsAndTheComputeStage) {
  for (const char* keys : {"sorted", "reverse", "duplicates", "few-distinct"})
    for (const char* stage : {"fragment", "compute"}) {
      auto v = run_case(
          "sort", {{"variant", "insertion-v2"}, {"memory", "registers"}, {"n", "8"}, {"keys", keys}, {"stage", stage}},
          kSmall);
      EXPECT_TRUE(v.valid) << "keys=" << keys << " stage=" << stage << ": " << v.reason;
    }
  auto v = run_case(
      "sort", {{"variant", "bitonic"}, {"memory", "local"}, {"n", "12"}, {"keys", "duplicates"}, {"stage", "compute"}},
      kSmall);
  EXPECT_TRUE(v.valid) << "bitonic compute: " << v.reason;
}

TEST_F(Sort, TableA1AssignmentsAllSort) {
  for (const char* assign : {"direct", "loop", "switch", "if-else"})
    for (const char* n : {"5", "16"}) {
      auto v = run_case("sort", {{"variant", "insertion-naive"}, {"memory", "registers"}, {"assign", assign}, {"n", n}},
                        kSmall);
      EXPECT_TRUE(v.valid) << "assign=" << assign << " n=" << n << ": " << v.reason;
    }
}

TEST_F(Sort, ValidatorCatchesAChangedPayloadAndAnOutOfOrderPair) {
  for (const char* stage : {"fragment", "compute"}) {
    auto v = run_case(
        "sort",
        {{"variant", "insertion-v2"}, {"memory", "registers"}, {"n", "8"}, {"stage", stage}, {"fault", "wrong-result"}},
        kSmall);
    EXPECT_FALSE(v.valid) << stage;
    EXPECT_EQ(v.metrics.at("unsorted_pixels"), "1") << stage << ": " << v.reason;
    // Pixel (1,1) has a payload flipped; pixel (2,1) only reordered, so its multiset is intact.
    EXPECT_EQ(v.metrics.at("changed_pixels"), "1") << stage << ": " << v.reason;
  }
}

// Mesa 22.3.6 llvmpipe loses the shifts of Listing 4.13's hole-index loop; the validator must
// report it rather than let a timing through. On a driver that compiles it correctly it passes.
TEST_F(Sort, ShellListingShapeIsValidatedNotTrusted) {
  auto v = run_case("sort", {{"variant", "shell"}, {"memory", "registers"}, {"n", "8"}}, kSmall);
  if (!v.valid) {
    EXPECT_NE(v.metrics.at("changed_pixels"), "0") << v.reason;
    RecordProperty("shell_driver_bug", v.reason);
  }
  EXPECT_TRUE(v.valid || gl().is_software_renderer()) << "shell invalid on a hardware driver: " << v.reason;
}

TEST_F(Sort, ImpossibleFormsAreUnsupportedWithAReason) {
  auto dir = temp_dir("sort_unsupported");
  auto out = dir / "rows.csv";
  auto r = run_oitbench({"run",          "sort",
                         "--set",        "variant=merge,rbs,bubble",
                         "--set",        "memory=local,registers",
                         "--set",        "n=4",
                         "--set",        "stage=fragment",
                         "--set",        "keys=random",
                         "--set",        "assign=listing,loop",
                         "--resolution", "8x8",
                         "--reps",       "1",
                         "--out",        out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  int unsupported = 0, ok = 0;
  for (const auto& row : read_csv_rows(out)) {
    if (row.at("status") == "unsupported") {
      ++unsupported;
      EXPECT_FALSE(row.at("reason").empty());
    } else {
      EXPECT_EQ(row.at("status"), "ok") << row.at("variant") << " " << row.at("reason");
      ++ok;
    }
  }
  // Of 3 variants x 2 memories x 2 assigns, merge+registers, rbs+local and every assign=loop are
  // impossible: 4 cases run.
  EXPECT_EQ(ok, 4);
  EXPECT_EQ(unsupported, 8);
}

}  // namespace oitbench::test
