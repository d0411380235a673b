// oit on the embedded default: capture keeps every fragment (and re-renders when the pool is too
// small), every resolve matches the CPU reference, BMA resolves each covered pixel exactly once,
// and the validator fails on a broken result.
#include <fstream>

#include "support/test_support.hpp"

namespace oitbench::test {

class Oit : public GlTest {};

namespace {
std::map<std::string, std::string> small(std::string scene, std::string view, std::string technique) {
  return {{"scene", scene}, {"view", view}, {"technique", technique}, {"detail", "small"}, {"block", "8"}};
}
}  // namespace

TEST_F(Oit, CaptureLosesNoFragmentAndOverflowRerenders) {
  auto p = small("planes", "fwd", "BASE-IS");
  p["initial_pool"] = "1000";  // far below 24 planes x 64 x 64: the first frame must overflow
  auto v = run_case("oit", p);
  EXPECT_TRUE(v.valid) << v.reason;
  EXPECT_EQ(v.metrics.at("total_fragments"), std::to_string(24 * 64 * 64));  // every plane covers every pixel
  EXPECT_GE(std::stoi(v.metrics.at("overflow_rerenders")), 1);
  // Steady state: the pool stays within 1.25x of the fragments captured.
  EXPECT_LE(std::stod(v.metrics.at("node_pool")), 1.25 * 24 * 64 * 64);
  EXPECT_EQ(v.metrics.at("peak_depth"), "24");
  EXPECT_EQ(v.metrics.at("max_frags_used"), "32");
}

// Without initial_pool a count pass sizes the pool before the first capture (exact_case.cpp: size_pool):
// nothing overflows, the pool is the fragments and the 1/32 a steady capture keeps, and the peak depth
// sets MAX_FRAGS as the lists' own would; BMA-AUTO captures into that pool for its calibration.
TEST_F(Oit, ACountPassSizesThePoolSoTheFirstCaptureNeverOverflows) {
  for (const char* technique : {"BASE-IS", "BMA-IS", "BMA-AUTO", "CPU-NATIVE"}) {
    auto p = small("planes", "rev", technique);
    if (std::string(technique) == "BMA-AUTO") p["bma_auto_cache"] = "off";
    auto v = run_case("oit", p);
    EXPECT_TRUE(v.valid) << technique << ": " << v.reason;
    const double fragments = 24 * 64 * 64;
    EXPECT_EQ(v.metrics.at("total_fragments"), std::to_string(24 * 64 * 64)) << technique;
    EXPECT_EQ(v.metrics.at("overflow_rerenders"), "0") << technique;
    EXPECT_GE(std::stod(v.metrics.at("node_pool")), fragments) << technique;
    EXPECT_LE(std::stod(v.metrics.at("node_pool")), fragments + fragments / 32 + 1) << technique;
    EXPECT_EQ(v.metrics.at("peak_depth"), "24") << technique;
    if (std::string(technique) != "CPU-NATIVE") {
      EXPECT_EQ(v.metrics.at("max_frags_used"), "32") << technique;
    }
  }
}

TEST_F(Oit, AnOversizedPoolShrinksBeforeTheNextFrameNotAfterIt) {
  auto p = small("planes", "rev", "BMA-RBS-L");
  p["initial_pool"] = "1000000";  // ten times what 24 planes at 64x64 need
  auto v = run_case("oit", p);
  EXPECT_TRUE(v.valid) << v.reason;
  EXPECT_EQ(v.metrics.at("overflow_rerenders"), "0");
  EXPECT_LE(std::stod(v.metrics.at("node_pool")), 1.25 * 24 * 64 * 64);
}

TEST_F(Oit, EveryResolveMatchesTheCpuReference) {
  for (const char* technique : {"BASE-IS", "BASE-IMS", "BASE-RBS-L", "BMA-IS", "BMA-IMS", "BMA-RBS-L", "CPU-NATIVE"})
    for (auto [scene, view] :
         {std::pair{"planes", "fwd"}, {"planes", "rev"}, {"hairball", "fwd"}, {"hairball", "rev"}}) {
      auto v = run_case("oit", small(scene, view, technique));
      EXPECT_TRUE(v.valid) << technique << " " << scene << " " << view << ": " << v.reason;
      EXPECT_EQ(v.metrics.at("bad_pixels"), "0");
      EXPECT_LE(std::stod(v.metrics.at("max_abs_error")), 2.0 / 255.0);
    }
}

TEST_F(Oit, MergeAndBlockPathsOnDeepPixels) {
  // 24 planes with MAX_FRAGS forced to 64: IMS takes its merge path (> 32 only for deeper lists, so
  // force small blocks for RBS: 4 per block, 16 blocks to merge).
  for (const char* technique : {"BASE-IMS", "BASE-RBS-L"}) {
    auto p = small("planes", "rev", technique);
    p["max_frags"] = "64";
    p["block"] = "4";
    auto v = run_case("oit", p);
    EXPECT_TRUE(v.valid) << technique << ": " << v.reason;
  }
  auto deep = small("smoke", "rev", "BMA-IMS");
  auto v = run_case("oit", deep, {96, 96});
  EXPECT_TRUE(v.valid) << v.reason;
}

TEST_F(Oit, PaperBlockSizeOf32) {
  auto p = small("planes", "rev", "BMA-RBS-L");
  p["block"] = "32";
  auto v = run_case("oit", p);
  EXPECT_TRUE(v.valid) << v.reason;
}

TEST_F(Oit, BmaResolvesEveryCoveredPixelExactlyOnce) {
  auto v = run_case("oit", small("hairball", "rev", "BMA-IS"));
  EXPECT_TRUE(v.valid) << v.reason;
  EXPECT_EQ(v.metrics.at("visit_errors"), "0");
  // The small hairball spans several intervals, so several programs and masks ran.
  EXPECT_NE(v.metrics.at("bma_intervals").find("16:"), std::string::npos) << v.metrics.at("bma_intervals");
}

TEST_F(Oit, TruncationIsReportedNotHidden) {
  auto p = small("planes", "fwd", "BASE-IS");
  p["max_frags"] = "16";
  auto v = run_case("oit", p);
  EXPECT_FALSE(v.valid);
  EXPECT_EQ(v.metrics.at("truncated_pixels"), std::to_string(64 * 64));
  EXPECT_NE(v.reason.find("truncated"), std::string::npos) << v.reason;
}

TEST_F(Oit, ValidatorCatchesAWrongResult) {
  for (const char* technique : {"BASE-IS", "BMA-RBS-L", "CPU-NATIVE"}) {
    auto p = small("planes", "fwd", technique);
    p["fault"] = "wrong-result";
    auto v = run_case("oit", p);
    EXPECT_FALSE(v.valid) << technique;
    EXPECT_NE(v.reason.find("differ from the CPU reference"), std::string::npos) << v.reason;
    EXPECT_EQ(v.metrics.at("bad_pixels"), "64") << technique;  // the diagonal
  }
}

TEST_F(Oit, MalformedSceneFileNamesFileAndLine) {
  auto dir = temp_dir("oit_scene");
  auto path = (dir / "broken.json").string();
  std::ofstream(path) << "{\n  \"materials\": {\n    \"glass\": { \"alpha\": 0.5, }\n  }\n}\n";
  try {
    run_case("oit", {{"scene", path}});
    FAIL() << "a malformed scene loaded";
  } catch (const std::exception& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find(path + ":3:"), std::string::npos) << msg;
    EXPECT_NE(msg.find("malformed JSON"), std::string::npos) << msg;
  }
}

TEST_F(Oit, QuickRunFromTheCommandLine) {
  auto out = temp_dir("oit_cli") / "oit.csv";
  auto r = run_oitbench({"run", "oit", "--quick", "--set", "scene=planes", "--set", "view=rev", "--set",
                         "technique=BMA-IS,CPU-NATIVE", "--resolution", "48x48", "--reps", "1", "--out", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto rows = read_csv_rows(out);
  int ok = 0;
  for (const auto& row : rows) ok += row.at("status") == "ok" && row.at("valid") == "1";
  EXPECT_EQ(ok, static_cast<int>(rows.size()));
  EXPECT_GE(rows.size(),
            8u);  // BMA: capture, count, mask, resolve, total; CPU-NATIVE: capture, readback, resolve, total
}

}  // namespace oitbench::test
