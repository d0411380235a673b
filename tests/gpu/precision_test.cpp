// Precision as a measured dimension (docs/precision.md): the fragment formats (frag_colour,
// frag_depth) of the exact techniques and the geometric reference of analytic scenes, on the
// precision-* scenes in scenes/. Every case of a planes-only scene is checked against both
// references (the captured fragments and the scene's own planes composited in double); a case the
// format or the driver cannot get right must be `invalid` with the reason, never `valid` and wrong.
#include <filesystem>
#include <string>
#include <vector>

#include "oit/oit_case.hpp"
#include "oit/techniques.hpp"
#include "support/test_support.hpp"

namespace oitbench::test {

class Precision : public GlTest {};

namespace {

std::map<std::string, std::string> params(const std::string& scene, const std::string& technique,
                                          const std::string& colour = "rgba8", const std::string& depth = "window") {
  return {{"scene", scene},        {"view", "fwd"},       {"technique", technique}, {"block", "8"},
          {"frag_colour", colour}, {"frag_depth", depth}, {"bma_auto_cache", "off"}};
}

double metric(const Validation& v, const std::string& name) { return std::stod(v.metrics.at(name)); }

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_F(Precision, ViewDepthKeepsLayersOneMicroApartInOrderInEveryExactTechnique) {
  // 8 layers 3e-6 apart at 3 units: every exact technique, both submission orders, both layouts.
  for (const auto& t : oit::technique_names(oit::TechniqueFamily::Exact))
    for (const char* view : {"fwd", "rev"}) {
      auto p = params("precision-ulp-3", t, "rgba8", "view");
      p["view"] = view;
      auto v = run_case("oit", p, {32, 32});
      EXPECT_TRUE(v.valid) << t << " " << view << ": " << v.reason;
      EXPECT_EQ(v.metrics.at("geometric_bad_pixels"), "0") << t << " " << view;
      EXPECT_EQ(v.metrics.at("tied_pixels"), "0") << t << " " << view;
      EXPECT_LE(metric(v, "truth_max_abs_error"), 2.0 / 255.0) << t << " " << view;
    }
  auto p = params("precision-ulp-3", "BASE-IS", "rgba32f", "view");
  p["capture"] = "PPPA";
  auto v = run_case("oit", p, {32, 32});
  EXPECT_TRUE(v.valid) << v.reason;
}

TEST_F(Precision, WindowDepthTiesThemAndTheGeometricReferenceSaysSo) {
  // The same case with window depth: the layers tie, go in colour order (the reverse of the true
  // one), and the reference built from the captured fragments agrees with that wrong image; only
  // the geometry catches it.
  for (const char* t : {"BASE-IS", "BMA-IS", "CPU-NATIVE"}) {
    auto v = run_case("oit", params("precision-ulp-3", t), {32, 32});
    EXPECT_FALSE(v.valid) << t;
    EXPECT_TRUE(has(v.reason, "differ from the geometric reference")) << t << ": " << v.reason;
    EXPECT_TRUE(has(v.reason, "frag_depth=window cannot separate them")) << t << ": " << v.reason;
    EXPECT_FALSE(has(v.reason, "from the CPU reference")) << t << ": " << v.reason;
    EXPECT_GT(metric(v, "tied_pixels"), 0) << t;
  }
  // At 1 unit (near plane 0.01) window depth fails too; view depth holds at 1 and 10 units.
  EXPECT_FALSE(run_case("oit", params("precision-ulp-1", "BASE-IS"), {32, 32}).valid);
  for (const char* scene : {"precision-ulp-1", "precision-ulp-10"}) {
    auto v = run_case("oit", params(scene, "BASE-IS", "rgba8", "view"), {32, 32});
    EXPECT_TRUE(v.valid) << scene << ": " << v.reason;
  }
}

TEST_F(Precision, FaintLayersNeedFloatColours) {
  // 5000 layers of alpha 1e-4: exact with rgba32f; rgba8 rounds every alpha to 0 and is valid
  // against its quantised references, its truth_rmse showing what the packing loses.
  for (const char* t : {"BASE-IS", "CPU-NATIVE"}) {
    auto f32 = run_case("oit", params("precision-faint-5000", t, "rgba32f"), {16, 16});
    ASSERT_TRUE(f32.valid) << t << ": " << f32.reason;
    EXPECT_EQ(f32.metrics.at("peak_depth"), "5000") << t;
    EXPECT_LT(metric(f32, "truth_rmse"), 1e-5) << t;
  }
  auto u8 = run_case("oit", params("precision-faint-5000", "CPU-NATIVE", "rgba8"), {16, 16});
  ASSERT_TRUE(u8.valid) << u8.reason;
  EXPECT_GT(metric(u8, "truth_rmse"), 0.01);
  // 1000 layers of alpha 1e-3: binary16 keeps them to its 2^-11 steps.
  auto f16 = run_case("oit", params("precision-faint-1000", "BASE-IS", "rgba16f"), {16, 16});
  ASSERT_TRUE(f16.valid) << f16.reason;
  EXPECT_LT(metric(f16, "truth_rmse"), 1e-3);
  auto u8k = run_case("oit", params("precision-faint-1000", "BASE-IS", "rgba8"), {16, 16});
  ASSERT_TRUE(u8k.valid) << u8k.reason;
  EXPECT_GT(metric(u8k, "truth_rmse"), 10 * metric(f16, "truth_rmse"));
}

TEST_F(Precision, EqualDepthsGiveOneAnswerInBothSubmissionOrders) {
  for (const char* colour : {"rgba8", "rgba16f", "rgba32f"})
    for (const char* t : {"BASE-IS", "BASE-RBS-L", "CPU-NATIVE"}) {
      auto ab = run_case("oit", params("precision-ties-ab", t, colour), {32, 32});
      auto ba = run_case("oit", params("precision-ties-ba", t, colour), {32, 32});
      ASSERT_TRUE(ab.valid) << t << " " << colour << ": " << ab.reason;
      ASSERT_TRUE(ba.valid) << t << " " << colour << ": " << ba.reason;
      EXPECT_EQ(ab.metrics.at("truth_rmse"), ba.metrics.at("truth_rmse")) << t << " " << colour;
      EXPECT_GT(metric(ab, "tied_pixels"), 0) << t;
    }
}

TEST_F(Precision, AlphaZeroAndOneNearAndFarOpaqueBetween) {
  for (const char* colour : {"rgba8", "rgba32f"})
    for (const char* t : {"BASE-IS", "BMA-IMS", "CPU-NATIVE"}) {
      for (const char* scene : {"precision-alpha-0-1", "precision-opaque-between"}) {
        auto v = run_case("oit", params(scene, t, colour), {32, 32});
        EXPECT_TRUE(v.valid) << scene << " " << t << " " << colour << ": " << v.reason;
        EXPECT_LE(metric(v, "truth_max_abs_error"), colour == std::string("rgba8") ? 2.0 / 255.0 : 1e-5)
            << scene << " " << t << " " << colour;
      }
      auto v = run_case("oit", params("precision-near-far", t, colour, "view"), {32, 32});
      EXPECT_TRUE(v.valid) << t << " " << colour << ": " << v.reason;
    }
  // The far pair (99.99 and 100 units, window depth 0.9999) ties in window depth.
  auto v = run_case("oit", params("precision-near-far", "BASE-IS"), {32, 32});
  EXPECT_FALSE(v.valid);
  EXPECT_TRUE(has(v.reason, "geometric reference")) << v.reason;
}

TEST_F(Precision, MoreLayersThanMaxFragsIsInvalidAgainstBothReferences) {
  auto p = params("precision-ulp-3", "BASE-IS", "rgba16f", "view");
  p["max_frags"] = "4";
  auto v = run_case("oit", p, {32, 32});
  EXPECT_FALSE(v.valid);
  EXPECT_TRUE(has(v.reason, "truncated")) << v.reason;
  EXPECT_TRUE(has(v.reason, "geometric reference")) << v.reason;
}

TEST_F(Precision, GeometricValidatorFailsOnADroppedLayer) {
  // fault=lose-fragment drops the diagonal's fragments at capture: the geometry counts the planes
  // those pixels should hold and names the first pixel that lost them.
  auto p = params("precision-ulp-3", "BASE-IS", "rgba8", "view");
  p["fault"] = "lose-fragment";
  auto v = run_case("oit", p, {32, 32});
  EXPECT_FALSE(v.valid);
  EXPECT_TRUE(has(v.reason, "another number of fragments than the scene's planes")) << v.reason;
  EXPECT_TRUE(has(v.reason, "differ from the geometric reference")) << v.reason;
  EXPECT_GT(metric(v, "geometric_bad_pixels"), 0);
}

TEST_F(Precision, NodeBytesFollowTheFormat) {
  // PPPA holds exactly the fragments (plus per-pixel counts and offsets): its pool bytes grow by
  // 4 and 12 bytes a fragment from rgba8 to rgba16f and rgba32f.
  std::map<std::string, double> bytes;
  for (const char* colour : {"rgba8", "rgba16f", "rgba32f"}) {
    auto p = params("precision-ulp-3", "BASE-IS", colour, "view");
    p["capture"] = "PPPA";
    auto v = run_case("oit", p, {32, 32});
    ASSERT_TRUE(v.valid) << colour << ": " << v.reason;
    bytes[colour] = metric(v, "node_pool_bytes") / metric(v, "node_pool");
    EXPECT_EQ(v.metrics.at("out_of_range_pixels"), "0");
    EXPECT_EQ(v.metrics.at("nonfinite"), "0");
  }
  EXPECT_NEAR(bytes["rgba16f"] - bytes["rgba8"], 4.0, 1e-9);
  EXPECT_NEAR(bytes["rgba32f"] - bytes["rgba8"], 12.0, 1e-9);
}

TEST_F(Precision, TruthColumnsOnAnalyticScenesOnly) {
  auto planes = run_case("oit", params("planes", "MLAB"), {32, 32});
  EXPECT_TRUE(planes.metrics.count("truth_rmse")) << "approximate techniques get the truth too";
  EXPECT_TRUE(planes.metrics.count("out_of_range_pixels"));
  auto smoke = run_case("oit", {{"scene", "smoke"}, {"technique", "BASE-IS"}, {"detail", "small"}}, {32, 32});
  EXPECT_FALSE(smoke.metrics.count("truth_rmse"));
  EXPECT_TRUE(smoke.metrics.count("out_of_range_pixels"));
}

// `render` writes the float image for approximate techniques too, and the row says whether any pixel
// lies outside [0, 1] (what the 8-bit PNG cannot show).
TEST(PrecisionCli, RenderWritesThePfmOfAnApproximateTechnique) {
  auto dir = temp_dir("render-approx");
  auto r = run_oitbench({"render", "--scene", "precision-ulp-3", "--technique", "WBOIT", "--resolution", "16x16",
                         "--out", (dir / "wboit.png").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(std::filesystem::file_size(dir / "wboit.pfm"), std::string("PF\n16 16\n-1.0\n").size() + 16 * 16 * 12);
  auto rows = read_csv_rows(dir / "wboit.csv");
  ASSERT_FALSE(rows.empty());
  EXPECT_EQ(rows.back()["out_of_range_pixels"], "0");
  EXPECT_FALSE(rows.back()["truth_rmse"].empty()) << "an analytic scene: the truth on an approximate row too";
}

}  // namespace oitbench::test
