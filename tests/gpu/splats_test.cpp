// Gaussian splats (issue 29) through the one splat rasteriser every technique shares (shaders/splats/,
// shaders/scene/fragment.glsl): the exact techniques match their reference on splat fragments with
// either depth key (splat_depth), each capture and resolve scheme, and their check fails on a wrong
// result; the approximate techniques run on splats with nothing of their own; GLOBAL-SORT (3DGS's
// per-frame sort of the splats by centre depth) matches its CPU model (each pixel's fragments in their
// splats' centre order), its check fails on a wrong order, it differs from the exact per-pixel
// reference, and a scene without splats is refused.
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
  for (const char* t : {"MLAB", "HT", "WBOIT", "unsorted"}) {
    auto v = run_case("oit", splat_case(t), {48, 48});
    EXPECT_GT(metric(v, "truth_rmse"), 0.0) << t;
  }
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
  std::map<std::string, std::string> p = {{"scene", "planes"}, {"view", "fwd"}, {"technique", "GLOBAL-SORT"}};
  EXPECT_THROW(run_case("oit", p, {32, 32}), Unsupported);
}

}  // namespace oitbench::test
