// The oit resolves added beside the paper's GLSL rows: compute-shader resolves (CS-*), RBS-G
// (blocks sorted in place in the lists' global memory), and BMA-AUTO (per-interval sort chosen by
// a calibration on this driver, cached). Each matches the CPU reference, and the validator fails
// when their output is perturbed.
#include <cstdlib>
#include <fstream>

#include <nlohmann/json.hpp>

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

TEST_F(OitCompute, ComputeGroupShapesAndDeepMergePaths) {
  // Load-then-sort is correct in every group shape (the stream form was not, with 4x4 groups).
  for (const char* group : {"8x8", "4x4"}) {
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
  // A cache naming RBS-L for every interval: BMA-AUTO must run exactly that (and stay valid).
  auto first = run_case("oit", small("planes", "rev", "BMA-AUTO"));
  ASSERT_TRUE(first.valid) << first.reason;
  auto path = cache_ / "oitbench" / "bma_auto.json";
  auto cache = nlohmann::json::parse(std::ifstream(path));
  for (auto& [key, entry] : cache.items()) entry["sort"] = "RBS-L";
  std::ofstream(path) << cache.dump();
  auto v = run_case("oit", small("planes", "rev", "BMA-AUTO"));
  EXPECT_TRUE(v.valid) << v.reason;
  EXPECT_EQ(v.metrics.at("bma_auto_choice"), "32:RBS-L");  // 24 planes: one interval, 17-32
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

TEST_F(OitCompute, MemoryIsReported) {
  auto v = run_case("oit", small("planes", "fwd", "CS-IS"));
  ASSERT_TRUE(v.valid) << v.reason;
  // 24 x 64 x 64 fragments in 12-byte nodes at least, plus 4-byte heads.
  EXPECT_GE(std::stoll(v.metrics.at("node_pool_bytes")), 24LL * 64 * 64 * 12 + 64 * 64 * 4);
}

}  // namespace oitbench::test
