// Gaussian splats (issue 29) through the one splat rasteriser every technique shares (shaders/splats/,
// shaders/scene/fragment.glsl): the exact techniques match their reference on splat fragments with
// either depth key (splat_depth), each capture and resolve scheme, and their check fails on a wrong
// result; the approximate techniques run on splats with nothing of their own; GLOBAL-SORT (3DGS's
// per-frame sort of the splats by centre depth) matches its CPU model (each pixel's fragments in their
// splats' centre order), its check fails on a wrong order, it differs from the exact per-pixel
// reference, and a scene without splats is refused (the technique table's primitives). WINDOW-SORT
// (StopThePop's windowed sort of that order) and FIRST-K (HTGS's K-only) match their CPU models, approach
// the analytic reference as the window or K grows, and their checks fail on a broken window. 3DGS's early
// termination (early_stop) in the ordered techniques matches references that stop at the same threshold.
#include "oit/techniques.hpp"
#include "support/test_support.hpp"

namespace oitbench::test {

class Splats : public GlTest {};

namespace {

std::map<std::string, std::string> splat_case(const std::string& technique, const std::string& depth = "ray-max") {
  return {{"scene", std::string(OITBENCH_TEST_DATA) + "/splats_gpu.json"},
          {"view", "fwd"},
          {"technique", technique},
          {"splat_depth", depth}};
}
double metric(const Validation& v, const std::string& name) { return std::stod(v.metrics.at(name)); }

}  // namespace

TEST_F(Splats, ExactTechniquesMatchTheirReferenceWithEitherKey) {
  for (const char* depth : {"ray-max", "centre"})
    for (const char* t : {"BASE-IS", "BMA-RBS-L", "CS-IMS", "CPU-NATIVE"}) {
      auto v = run_case("oit", splat_case(t, depth), {48, 48});
      EXPECT_TRUE(v.valid) << t << " splat_depth=" << depth << ": " << v.reason;
      EXPECT_GT(std::stol(v.metrics.at("total_fragments")), 0) << t;
      EXPECT_GT(std::stol(v.metrics.at("peak_depth")), 1) << t << ": the splats overlap";
      // the analytic reference (splat_reference.hpp), which shares nothing with the capture, agrees
      EXPECT_EQ(v.metrics.at("geometric_bad_pixels"), "0") << t << " " << depth;
      EXPECT_LE(metric(v, "truth_max_abs_error"), 2.0 / 255.0) << t << " " << depth;
    }
}

TEST_F(Splats, PackedArraysMatchTheirReference) {
  auto p = splat_case("BASE-IS");
  p["capture"] = "PPPA";
  auto v = run_case("oit", p, {48, 48});
  EXPECT_TRUE(v.valid) << v.reason;
}

TEST_F(Splats, TheAnalyticCheckFailsOnAWrongResult) {
  for (const char* t : {"BASE-IS", "CS-IMS"}) {
    auto p = splat_case(t);
    p["fault"] = "wrong-result";
    auto v = run_case("oit", p, {48, 48});
    EXPECT_FALSE(v.valid) << t;
    EXPECT_GT(std::stol(v.metrics.at("geometric_bad_pixels")), 0) << t << ": " << v.reason;
    EXPECT_NE(v.reason.find("analytic splat reference"), std::string::npos) << v.reason;
  }
}

TEST_F(Splats, ApproximateTechniquesRunThroughTheSameRasteriser) {
  for (const char* t : {"MLAB", "HT", "WBOIT", "STOCHASTIC", "SLAB", "DP", "unsorted"}) {
    auto v = run_case("oit", splat_case(t), {48, 48});
    EXPECT_TRUE(v.valid) << t << ": " << v.reason;
  }
  // the approximations held to their own models report their error against the analytic reference
  for (const char* t : {"MLAB", "HT", "WBOIT", "unsorted", "STOCHASTIC", "SLAB"}) {
    auto v = run_case("oit", splat_case(t), {48, 48});
    EXPECT_GT(metric(v, "truth_rmse"), 0.0) << t;
  }
  // depth peeling run to completion is exact: its analytic error is the exact techniques'
  auto dp = run_case("oit", splat_case("DP"), {48, 48});
  EXPECT_LE(metric(dp, "truth_max_abs_error"), 2.0 / 255.0) << dp.reason;
}

TEST_F(Splats, GlobalSortMatchesItsModelNotTheExactReference) {
  for (const char* depth : {"ray-max", "centre"}) {
    auto v = run_case("oit", splat_case("GLOBAL-SORT", depth), {48, 48});
    EXPECT_TRUE(v.valid) << depth << ": " << v.reason;
    EXPECT_LE(metric(v, "model_max_diff"), 3.0 / 255.0) << depth;
    EXPECT_GT(metric(v, "rmse"), 0.0) << depth << ": the centres' order is not the per-pixel order";
    EXPECT_GT(metric(v, "truth_rmse"), 0.0) << depth;
  }
}

TEST_F(Splats, TheGlobalSortCheckFailsOnAWrongOrder) {
  auto p = splat_case("GLOBAL-SORT");
  p["fault"] = "wrong-result";
  auto v = run_case("oit", p, {48, 48});
  EXPECT_FALSE(v.valid);
  EXPECT_NE(v.reason.find("CPU model"), std::string::npos) << v.reason;
}

// MBOIT's and WOIT's depth warp is bounded by the mesh's vertices: on splats (none) it would be degenerate,
// an image that matches its model and not the scene (MBOIT's error 0.40 against the exact image).
TEST_F(Splats, MomentsAndWaveletsRefuseSplatsUntilTheirWarpIsBoundedBySplats) {
  for (const char* t : {"MBOIT", "WOIT"}) {
    try {
      run_case("oit", splat_case(t), {48, 48});
      ADD_FAILURE() << t << " ran on splats";
    } catch (const Unsupported& e) {
      EXPECT_NE(std::string(e.what()).find("only splats"), std::string::npos) << e.what();
    }
  }
}

TEST_F(Splats, GlobalSortOfAMeshIsUnsupported) {
  for (const char* t : {"GLOBAL-SORT", "WINDOW-SORT"}) {
    std::map<std::string, std::string> p = {{"scene", "planes"}, {"view", "fwd"}, {"technique", t}};
    try {
      run_case("oit", p, {32, 32});
      ADD_FAILURE() << t << " ran on a mesh";
    } catch (const Unsupported& e) {  // from the technique table's primitives, not from the technique's name
      EXPECT_NE(std::string(e.what()).find("primitives: splats"), std::string::npos) << e.what();
    }
  }
  for (const auto& t : oit::techniques())
    if (t.name == "GLOBAL-SORT" || t.name == "WINDOW-SORT") {
      EXPECT_EQ(t.primitives, oit::TechniquePrimitives::Splats);
    }
}

// 3DGS's early termination (early_stop): each ordered technique composites front to back and stops at the
// fragment that would take the transmittance below the threshold, matching references that stop there (the
// exact ones the analytic splat reference, GLOBAL-SORT its CPU model). At 0.3 the test scene's dense pixels
// stop; the same case blending every fragment (fault=no-early-stop) is another image, and its checks fail.
TEST_F(Splats, EarlyStopMatchesReferencesThatStopAndTheirChecksFailWithoutIt) {
  // RBS-L: its merge (BASE), the one-block form of BMA's short intervals, and the order check's paths (CS)
  for (const char* t :
       {"BASE-IS", "BMA-IMS", "CS-IS", "CPU-NATIVE", "GLOBAL-SORT", "BASE-RBS-L", "BMA-RBS-L", "CS-RBS-L"}) {
    auto p = splat_case(t);
    p["early_stop"] = "0.3";
    if (std::string(t) == "CS-RBS-L" || std::string(t) == "BMA-RBS-L") p["order_check"] = "on";
    auto v = run_case("oit", p, {48, 48});
    EXPECT_TRUE(v.valid) << t << ": " << v.reason;
    if (std::string(t) != "GLOBAL-SORT") {
      EXPECT_EQ(v.metrics.at("geometric_bad_pixels"), "0") << t;
    }
    p["fault"] = "no-early-stop";
    auto broken = run_case("oit", p, {48, 48});
    EXPECT_FALSE(broken.valid) << t << ": blending every fragment passed the checks of early_stop=0.3";
    if (std::string(t) == "GLOBAL-SORT")
      EXPECT_NE(broken.reason.find("CPU model"), std::string::npos) << broken.reason;
    else
      EXPECT_GT(std::stol(broken.metrics.at("geometric_bad_pixels")), 0) << t << ": " << broken.reason;
  }
}

// 3DGS's own threshold, written as 3DGS writes it (1e-4: a GLSL literal in the resolve's EARLY_STOP).
TEST_F(Splats, EarlyStopAt3dgsThresholdIsValid) {
  for (const char* t : {"BASE-IS", "GLOBAL-SORT"}) {
    auto p = splat_case(t);
    p["early_stop"] = "1e-4";
    auto v = run_case("oit", p, {48, 48});
    EXPECT_TRUE(v.valid) << t << ": " << v.reason;
  }
}

// The windowed sort over the global order: valid against its CPU model with either key (with the centre key
// the window changes nothing: the global order is already the per-pixel one), closer to the analytic
// reference with a wider window, and a window of 64 (the scene's lists hold up to 120 fragments, none that
// far out of place) matches the exact composite of the same fragments.
TEST_F(Splats, WindowSortMatchesItsModelAndApproachesTheReference) {
  double rmse[3] = {0, 0, 0};
  const char* windows[3] = {"1", "4", "64"};
  for (int i = 0; i < 3; ++i) {
    auto p = splat_case("WINDOW-SORT");
    p["window"] = windows[i];
    auto v = run_case("oit", p, {48, 48});
    EXPECT_TRUE(v.valid) << "window " << windows[i] << ": " << v.reason;
    EXPECT_LE(metric(v, "model_max_diff"), 3.0 / 255.0) << windows[i];
    rmse[i] = metric(v, "truth_rmse");
    if (i == 2) {
      EXPECT_LE(metric(v, "rmse"), 1e-5) << "the exact composite of the captured fragments";
      // and the analytic reference, as closely as the exact techniques (their 2/255)
      EXPECT_LE(metric(v, "truth_max_abs_error"), 2.0 / 255.0);
      EXPECT_EQ(v.metrics.at("geometric_bad_pixels"), "0");
    }
  }
  EXPECT_GT(rmse[0], 2 * rmse[1]) << "a window of 1 leaves fragments out of place that one of 4 sorts";
  EXPECT_GT(rmse[1], rmse[2]);
  auto global = run_case("oit", splat_case("GLOBAL-SORT"), {48, 48});
  EXPECT_GT(metric(global, "truth_rmse"), rmse[0]) << "even a window of 1 reorders some of the global order";
  auto centre = run_case("oit", splat_case("WINDOW-SORT", "centre"), {48, 48});
  EXPECT_TRUE(centre.valid) << centre.reason;
  EXPECT_LE(metric(centre, "rmse"), 1e-5) << "the centre order is the centre key's order";
  EXPECT_LE(metric(centre, "truth_max_abs_error"), 2.0 / 255.0);
}

// fault=wrong-result blends each arriving fragment instead of the window's nearest (besides the resolve's
// diagonal, 48 channels at 48x48, and the key pass's first splat): the model check sees far more.
TEST_F(Splats, TheWindowSortCheckFailsOnABrokenWindow) {
  auto p = splat_case("WINDOW-SORT");
  p["fault"] = "wrong-result";
  auto v = run_case("oit", p, {48, 48});
  EXPECT_FALSE(v.valid);
  const size_t at = v.reason.find(" channel value(s) differ from the technique's CPU model");
  ASSERT_NE(at, std::string::npos) << v.reason;
  const size_t start = v.reason.rfind(' ', at - 1) + 1;
  EXPECT_GT(std::stol(v.reason.substr(start, at - start)), 48 * 3) << v.reason;
}

// FIRST-K keeps each pixel's K nearest fragments and drops the rest: HT without its tail. What it drops
// shows against the reference: far less with K = 64 (one pixel's list is longer) than with K = 2.
TEST_F(Splats, FirstKMatchesItsModelAndLosesWhatItDrops) {
  double rmse[2] = {0, 0};
  const char* ks[2] = {"2", "64"};
  for (int i = 0; i < 2; ++i) {
    auto p = splat_case("FIRST-K");
    p["nodes"] = ks[i];
    auto v = run_case("oit", p, {48, 48});
    EXPECT_TRUE(v.valid) << "K " << ks[i] << ": " << v.reason;
    EXPECT_LE(metric(v, "model_max_diff"), 3.0 / 255.0) << ks[i];
    rmse[i] = metric(v, "truth_rmse");
  }
  EXPECT_GT(rmse[0], 0.1) << "two nodes drop most of what lies behind them";
  EXPECT_LT(rmse[1], 2e-3);
  auto p = splat_case("FIRST-K");
  p["fault"] = "wrong-result";
  auto v = run_case("oit", p, {48, 48});
  EXPECT_FALSE(v.valid);
  EXPECT_NE(v.reason.find("CPU model"), std::string::npos) << v.reason;
}

// HT with HTGS's configuration: valid against its model, and not Maule's (faint fragments go to the tail,
// whose coverage is the product of its transmittances), so even a core as deep as the lists is not exact.
TEST_F(Splats, HtWithHtgsConfigurationMatchesItsModel) {
  auto p = splat_case("HT");
  p["nodes"] = "64";
  p["ht_variant"] = "htgs";
  auto htgs = run_case("oit", p, {48, 48});
  EXPECT_TRUE(htgs.valid) << htgs.reason;
  EXPECT_LE(metric(htgs, "model_max_diff"), 3.0 / 255.0);
  p["ht_variant"] = "maule";
  auto maule = run_case("oit", p, {48, 48});
  EXPECT_TRUE(maule.valid) << maule.reason;
  EXPECT_GT(metric(htgs, "rmse"), 10 * metric(maule, "rmse")) << "HTGS's faint fragments skip the core";
  p["ht_variant"] = "htgs";
  p["fault"] = "wrong-result";
  EXPECT_FALSE(run_case("oit", p, {48, 48}).valid);
}
}  // namespace oitbench::test
