// The oit resolves added beside the paper's GLSL rows: compute-shader resolves (CS-*), RBS-G
// (blocks sorted in place in the lists' global memory), and BMA-AUTO (per-interval sort chosen by
// a calibration on this driver, cached). Each matches the CPU reference, and the validator fails
// when their output is perturbed.
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "support/test_support.hpp"

namespace oitbench::test {

class OitCompute : public GlTest {
 protected:
  void SetUp() override {
    GlTest::SetUp();
    // BMA-AUTO's choices go to a per-test cache, never the user's ~/.cache.
    cache_ = temp_dir("oit_bma_auto_cache");
    setenv("XDG_CACHE_HOME", cache_.c_str(), 1);
  }
  std::filesystem::path cache_;
};

namespace {
std::map<std::string, std::string> small(std::string scene, std::string view, std::string technique) {
  return {{"scene", scene}, {"view", view}, {"technique", technique}, {"detail", "small"}, {"block", "8"}};
}
}  // namespace

TEST_F(OitCompute, ComputeResolvesAndRbsGMatchTheCpuReference) {
  for (const char* technique : {"CS-IS", "CS-IMS", "CS-RBS-L", "RBS-G"})
    for (auto [scene, view] : {std::pair{"planes", "rev"}, {"hairball", "fwd"}, {"hairball", "rev"}}) {
      auto v = run_case("oit", small(scene, view, technique));
      EXPECT_TRUE(v.valid) << technique << " " << scene << " " << view << ": " << v.reason;
      EXPECT_EQ(v.metrics.at("bad_pixels"), "0");
      EXPECT_EQ(v.metrics.at("visit_errors"), "0");
    }
}

// The register networks as RBS's block sort: blocks of 8 (4 blocks and a merge on the 24 planes;
// blocks padded where the hairball's pixels hold fewer), every RBS form.
TEST_F(OitCompute, NetworkBlockSortsMatchTheCpuReference) {
  for (const char* block_sort : {"bitonic", "odd-even-merge"})
    for (const char* technique : {"BASE-RBS-L", "CS-RBS-L", "RBS-G"})
      for (auto [scene, view] : {std::pair{"planes", "rev"}, {"hairball", "rev"}}) {
        auto p = small(scene, view, technique);
        p["block_sort"] = block_sort;
        auto v = run_case("oit", p);
        EXPECT_TRUE(v.valid) << technique << " " << block_sort << " " << scene << " " << view << ": " << v.reason;
      }
  // rgba16f does not pack into one 64-bit key: the select form of the compare-exchange.
  auto p = small("hairball", "rev", "CS-RBS-L");
  p["block_sort"] = "bitonic";
  p["frag_colour"] = "rgba16f";
  auto v = run_case("oit", p);
  EXPECT_TRUE(v.valid) << "rgba16f: " << v.reason;
}

// The order check: sorted lists (fwd) skip the sort, reversed ones (rev) are reversed, mixed ones
// (the hairball) are sorted; IS, IMS and RBS-L (its blocks of 8 merged, or one block of 32 with
// max_frags 32, networks and RS), fragment and compute resolves, PPLL and PPPA (which holds each
// pixel in PPLL's order, packed_arrays.glsl).
TEST_F(OitCompute, OrderCheckedResolvesMatchTheCpuReference) {
  for (const char* technique : {"BASE-IS", "CS-IMS", "BMA-IS", "CS-RBS-L", "BASE-RBS-L", "BMA-RBS-L"})
    for (const char* capture : {"PPLL", "PPPA"})
      for (auto [scene, view] : {std::pair{"planes", "fwd"}, {"planes", "rev"}, {"hairball", "rev"}}) {
        auto p = small(scene, view, technique);
        p["order_check"] = "on";
        p["capture"] = capture;
        if (std::string(technique) == "CS-RBS-L") p["block_sort"] = "bitonic";
        if (std::string(technique) == "BMA-RBS-L") {  // one block: RBS-L's path without a merge
          p["block"] = "32";
          p["max_frags"] = "32";
          p["block_sort"] = "odd-even-merge";
        }
        auto v = run_case("oit", p);
        EXPECT_TRUE(v.valid) << technique << " " << capture << " " << scene << " " << view << ": " << v.reason;
      }
  for (const char* technique : {"BASE-IS", "CS-RBS-L", "BASE-RBS-L"}) {
    auto p = small("planes", "rev", technique);
    if (std::string(technique) != "CS-RBS-L") p["order_check"] = "on";
    if (std::string(technique) != "BASE-IS") p["block_sort"] = "bitonic";
    p["fault"] = "wrong-result";
    auto v = run_case("oit", p);
    EXPECT_FALSE(v.valid) << technique;
    EXPECT_EQ(v.metrics.at("bad_pixels"), "64") << technique;  // the diagonal
  }
}

TEST_F(OitCompute, ComputeGroupShapesAndDeepMergePaths) {
  // Load-then-sort is correct in every group shape (the stream form was not, with 4x4 groups): 8x8 (the
  // default) and 4x4 lay invocations over 4x4-pixel blocks, 8x1 and 64x1 over rows (resolve.comp's
  // group_pixel(); a mapping that skips or repeats a pixel leaves pixels unresolved, and invalid).
  for (const char* group : {"8x1", "4x4", "64x1"}) {
    auto p = small("hairball", "rev", "CS-IS");
    p["cs_group"] = group;
    auto v = run_case("oit", p);
    EXPECT_TRUE(v.valid) << group << ": " << v.reason;
  }
  // 24 planes with MAX_FRAGS 64 and 4-fragment blocks: IMS merges, RBS-G merges 16 blocks in global memory.
  for (const char* technique : {"CS-IMS", "CS-RBS-L", "RBS-G"}) {
    auto p = small("planes", "rev", technique);
    p["max_frags"] = "64";
    p["block"] = "4";
    auto v = run_case("oit", p);
    EXPECT_TRUE(v.valid) << technique << ": " << v.reason;
  }
}

TEST_F(OitCompute, BmaAutoCalibratesOnceThenReadsTheCache) {
  auto p = small("hairball", "rev", "BMA-AUTO");
  auto first = run_case("oit", p);
  EXPECT_TRUE(first.valid) << first.reason;
  EXPECT_EQ(first.metrics.at("bma_auto_source"), "calibrated");
  std::string choice = first.metrics.at("bma_auto_choice");
  EXPECT_NE(choice.find("8:"), std::string::npos) << choice;
  EXPECT_NE(choice.find("16:"), std::string::npos) << choice;  // the small hairball spans several intervals

  auto path = cache_ / "oitbench" / "bma_auto.json";
  ASSERT_TRUE(std::filesystem::exists(path));
  auto cache = nlohmann::json::parse(std::ifstream(path));
  EXPECT_GE(cache.size(), 2u);
  for (const auto& [key, entry] : cache.items()) {
    EXPECT_NE(key.find("interval"), std::string::npos) << key;
    EXPECT_TRUE(entry.contains("sort")) << key;
  }

  auto second = run_case("oit", p);
  EXPECT_TRUE(second.valid) << second.reason;
  EXPECT_EQ(second.metrics.at("bma_auto_source"), "cached");
  EXPECT_EQ(second.metrics.at("bma_auto_choice"), choice);
}

TEST_F(OitCompute, BmaAutoFollowsAForcedCacheEntry) {
  // A cache naming one sort for every interval: BMA-AUTO must run exactly that (and stay valid);
  // RBS-L with the network and the order check is a candidate the calibration times, too.
  auto first = run_case("oit", small("planes", "rev", "BMA-AUTO"));
  ASSERT_TRUE(first.valid) << first.reason;
  EXPECT_NE(first.metrics.at("bma_auto_timings").find("RBS-L/bitonic+order-check="), std::string::npos)
      << first.metrics.at("bma_auto_timings");
  auto path = cache_ / "oitbench" / "bma_auto.json";
  for (const char* sort : {"RBS-L", "RBS-L/bitonic+order-check"}) {
    auto cache = nlohmann::json::parse(std::ifstream(path));
    for (auto& [key, entry] : cache.items()) {
      EXPECT_NE(key.find("candidates 3"), std::string::npos) << key;
      entry["sort"] = sort;
    }
    std::ofstream(path) << cache.dump();
    auto v = run_case("oit", small("planes", "rev", "BMA-AUTO"));
    EXPECT_TRUE(v.valid) << sort << ": " << v.reason;
    EXPECT_EQ(v.metrics.at("bma_auto_choice"), std::string("32:") + sort);  // 24 planes: one interval, 17-32
  }
}

TEST_F(OitCompute, BmaAutoKeysTheCacheOnTheListOrder) {
  // Sorted lists (fwd) and reverse-sorted ones (rev) are different inputs for insertion sort: the
  // choice made on one must not be reused on the other.
  auto fwd = run_case("oit", small("planes", "fwd", "BMA-AUTO"));
  ASSERT_TRUE(fwd.valid) << fwd.reason;
  auto rev = run_case("oit", small("planes", "rev", "BMA-AUTO"));
  ASSERT_TRUE(rev.valid) << rev.reason;
  EXPECT_EQ(rev.metrics.at("bma_auto_source"), "calibrated");
  EXPECT_NE(fwd.metrics.at("bma_auto_timings").find("32/sorted:"), std::string::npos)
      << fwd.metrics.at("bma_auto_timings");
  EXPECT_NE(rev.metrics.at("bma_auto_timings").find("32/reverse:"), std::string::npos)
      << rev.metrics.at("bma_auto_timings");
  auto cache = nlohmann::json::parse(std::ifstream(cache_ / "oitbench" / "bma_auto.json"));
  EXPECT_EQ(cache.size(), 2u);
}

TEST_F(OitCompute, BmaAutoWithoutTheCacheCalibratesEveryCase) {
  auto p = small("planes", "rev", "BMA-AUTO");
  p["bma_auto_cache"] = "off";
  for (int i = 0; i < 2; ++i) {
    auto v = run_case("oit", p);
    EXPECT_TRUE(v.valid) << v.reason;
    EXPECT_EQ(v.metrics.at("bma_auto_source"), "calibrated");
  }
  EXPECT_FALSE(std::filesystem::exists(cache_ / "oitbench" / "bma_auto.json"));
}

TEST_F(OitCompute, ValidatorCatchesAWrongResult) {
  for (const char* technique : {"CS-IS", "CS-RBS-L", "RBS-G", "BMA-AUTO"}) {
    auto p = small("planes", "fwd", technique);
    p["fault"] = "wrong-result";
    auto v = run_case("oit", p);
    EXPECT_FALSE(v.valid) << technique;
    EXPECT_EQ(v.metrics.at("bad_pixels"), "64") << technique;  // the diagonal
  }
}

TEST_F(OitCompute, LlvmpipeLoopBudgetIsCaughtAndNamed) {
  // 1100 reverse-sorted fragments per pixel: RBS's merge (1100 x 64 steps) passes the 65535 loop
  // iterations llvmpipe allows an invocation, its loops stop early and every pixel is wrong. The
  // validator must say so (on a real GPU the same case is simply valid).
  if (!gl().is_software_renderer()) GTEST_SKIP() << "the loop budget is llvmpipe's";
  auto v = run_case("oit", {{"scene", "planes-deep"}, {"view", "rev"}, {"technique", "BASE-RBS-L"}}, {8, 8});
  EXPECT_FALSE(v.valid);
  EXPECT_EQ(v.metrics.at("peak_depth"), "1100");
  EXPECT_NE(v.reason.find("65535"), std::string::npos) << v.reason;
}

TEST_F(OitCompute, MemoryIsReported) {
  auto v = run_case("oit", small("planes", "fwd", "CS-IS"));
  ASSERT_TRUE(v.valid) << v.reason;
  // 24 x 64 x 64 fragments in 12-byte nodes at least, plus 4-byte heads.
  EXPECT_GE(std::stoll(v.metrics.at("node_pool_bytes")), 24LL * 64 * 64 * 12 + 64 * 64 * 4);
}

TEST_F(OitCompute, QuickKnowlesPresetsRunEndToEnd) {
  // Every row of the quick paper grids is a valid result or says why not.
  for (const char* preset : {"knowles2014-quick", "knowles2013-quick"}) {
    auto out = temp_dir("oit_presets") / (std::string(preset) + ".csv");
    std::filesystem::remove(out);
    auto r = run_oitbench({"run", "--preset", preset, "--out", out.string()});
    ASSERT_EQ(r.exit_code, 0) << preset << ": " << r.err;
    auto rows = read_csv_rows(out);
    EXPECT_GE(rows.size(), 12u) << preset;
    std::set<std::string> techniques;
    for (const auto& row : rows) {
      techniques.insert(row.at("technique"));
      bool valid = row.at("status") == "ok" && row.at("valid") == "1";
      EXPECT_TRUE(valid || !row.at("reason").empty())
          << preset << " " << row.at("scene") << " " << row.at("technique") << ": " << row.at("status");
    }
    EXPECT_EQ(techniques.count("BMA-AUTO"), 1u) << preset;
    if (std::string(preset) == "knowles2014-quick") {
      EXPECT_EQ(techniques.size(), 12u);
    }
  }
}

}  // namespace oitbench::test
