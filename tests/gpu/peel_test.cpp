// oit's depth peeling (DP, DDP) and hybrid transparency (HT): run to completion DP and DDP are the
// exact composite on every scene, exactly tied depths included (the tie rule); classic peeling by
// depth alone loses coplanar fragments and its validator says so; max_layers makes an approximation
// validated against its CPU model, with less error for more layers; the fault makes every
// validator fail; and every technique's row carries bytes_per_pixel.
#include "oit/peel/peel.hpp"

#include <cmath>
#include <string>

#include "oit/approx/approx.hpp"
#include "oit/oit_case.hpp"
#include "oit/techniques.hpp"
#include "support/test_support.hpp"

namespace oitbench::test {

class Peel : public GlTest {};

namespace {

std::string data(const std::string& name) { return std::string(OITBENCH_TEST_DATA) + "/" + name + ".json"; }

std::map<std::string, std::string> params(const std::string& scene, const std::string& technique,
                                          const std::string& view = "rev") {
  return {{"scene", scene}, {"view", view}, {"technique", technique}, {"detail", "small"}};
}

double metric(const Validation& v, const std::string& name) { return std::stod(v.metrics.at(name)); }

}  // namespace

TEST_F(Peel, RunToCompletionIsTheExactCompositeOnEveryScene) {
  for (const char* t : {"DP", "DDP"})
    for (const char* scene : {"planes", "hairball", "smoke"}) {
      auto v = run_case("oit", params(scene, t));
      ASSERT_TRUE(v.valid) << t << " " << scene << ": " << v.reason;
      EXPECT_EQ(v.metrics.at("peel_complete"), "yes") << t << " " << scene;
      EXPECT_LT(metric(v, "rmse"), 1e-5) << t << " " << scene;
      // The occlusion query ended the peel when the deepest pixel ran out of layers.
      double layers = metric(v, "layers_peeled");
      EXPECT_GE(layers, 1) << t << " " << scene;
      double per = std::string(t) == "DDP" ? 2 : 1;
      EXPECT_EQ(metric(v, "peel_passes"), 2 * (std::ceil(layers / per) + 1)) << t << " " << scene;
    }
}

TEST_F(Peel, ExactlyTiedDepthsArePeeledOnceEachInTheReferenceOrder) {
  for (const char* t : {"DP", "DDP"}) {
    auto p = params(data("hard_equal_depth"), t, "fwd");
    auto v = run_case("oit", p, {32, 32});
    ASSERT_TRUE(v.valid) << t << ": " << v.reason;
    EXPECT_EQ(v.metrics.at("tied_pixels"), std::to_string(32 * 32));
    EXPECT_LT(metric(v, "rmse"), 1e-5) << t;
    EXPECT_EQ(v.metrics.at("layers_peeled"), "24") << t;  // 24 planes of one depth: 24 (depth, colour) layers
  }
}

TEST_F(Peel, PeelingByDepthAloneLosesTiedFragmentsAndIsInvalid) {
  for (const char* t : {"DP", "DDP"}) {
    auto p = params(data("hard_equal_depth"), t, "fwd");
    p["tie_rule"] = "depth";
    auto tied = run_case("oit", p, {32, 32});
    EXPECT_FALSE(tied.valid) << t << ": the validator must notice the lost fragments";
    EXPECT_NE(tied.reason.find("exact reference"), std::string::npos) << tied.reason;
    EXPECT_EQ(tied.metrics.at("layers_peeled"), "1") << t;
    // Without ties the classic rule is exact.
    auto q = params("planes", t);
    q["tie_rule"] = "depth";
    auto plain = run_case("oit", q);
    EXPECT_TRUE(plain.valid) << t << ": " << plain.reason;
    EXPECT_LT(metric(plain, "rmse"), 1e-5) << t;
  }
}

TEST_F(Peel, MaxLayersIsAnApproximationWithItsErrorAsData) {
  for (const char* t : {"DP", "DDP"}) {
    double last = 1.0;
    for (const char* layers : {"2", "6", "12"}) {
      auto p = params("hairball", t);
      p["max_layers"] = layers;
      auto v = run_case("oit", p);
      ASSERT_TRUE(v.valid) << t << " " << layers << ": " << v.reason;
      EXPECT_EQ(v.metrics.at("peel_complete"), "no") << t << " " << layers;
      EXPECT_EQ(v.metrics.at("layers_peeled"), layers) << t;
      EXPECT_LE(metric(v, "model_max_diff"), 1e-4) << t << " " << layers;
      double e = metric(v, "rmse");
      EXPECT_GT(e, 1e-4) << t << " " << layers << ": layers were left out";
      EXPECT_LT(e, last) << t << " " << layers << ": more layers, less error";
      last = e;
    }
  }
}

TEST_F(Peel, DualPeelingTakesHalfTheIterations) {
  auto dp = run_case("oit", params("planes", "DP"));
  auto ddp = run_case("oit", params("planes", "DDP"));
  ASSERT_TRUE(dp.valid && ddp.valid) << dp.reason << ddp.reason;
  EXPECT_EQ(dp.metrics.at("peel_passes"), "50");  // 24 layers: 24 iterations + the one that finds none
  EXPECT_EQ(ddp.metrics.at("peel_passes"), "26");
}

TEST_F(Peel, AWrongResultFailsEveryValidator) {
  for (const char* t : {"DP", "DDP", "HT"}) {
    auto p = params("planes", t);
    p["fault"] = "wrong-result";
    auto v = run_case("oit", p);
    EXPECT_FALSE(v.valid) << t;
    EXPECT_NE(v.reason.find("CPU model"), std::string::npos) << t << ": " << v.reason;
    if (std::string(t) != "HT") {
      p["max_layers"] = "3";  // the approximation's validator too
      auto a = run_case("oit", p);
      EXPECT_FALSE(a.valid) << t;
    }
  }
}

TEST_F(Peel, HybridTransparencyIsExactWithACoreAsDeepAsThePixelsAndErrsWithLess) {
  auto p = params("hairball", "HT");
  p["nodes"] = "4";
  auto few = run_case("oit", p);
  p["nodes"] = "32";  // at least the small hairball's peak depth: the tail stays empty
  auto many = run_case("oit", p);
  ASSERT_TRUE(few.valid && many.valid) << few.reason << many.reason;
  EXPECT_LT(metric(many, "rmse"), 1e-5);
  EXPECT_GT(metric(few, "rmse"), 1e-4);
  EXPECT_EQ(few.metrics.at("capped_updates"), "0");
}

TEST_F(Peel, PeelingLeavesNoBlendStateForTheNextCase) {
  // The peel's MAX blending of its min-max target once stayed on draw buffer 1, where HT's tail then
  // took the max of its count instead of the sum.
  for (const char* t : {"DP", "DDP"}) {
    ASSERT_TRUE(run_case("oit", params("hairball", t)).valid) << t;
    auto p = params("hairball", "HT");
    p["nodes"] = "4";
    auto v = run_case("oit", p);
    EXPECT_TRUE(v.valid) << "HT after " << t << ": " << v.reason;
  }
}

TEST_F(Peel, EveryTechniqueRowCarriesItsBytesPerPixel) {
  // Those that draw meshes (the table's primitives: GLOBAL-SORT draws only splats, gpu.Splats).
  std::vector<std::string> all;
  for (auto f : {oit::TechniqueFamily::Exact, oit::TechniqueFamily::Approximate, oit::TechniqueFamily::Peel})
    for (const auto& a : oit::technique_names_on_meshes(f)) all.push_back(a);
  for (const auto& t : all) {
    if (t == "BMA-AUTO") continue;  // calibrates first: slow here, and its storage is BMA's
    auto p = params("planes", t, "fwd");
    auto v = run_case("oit", p, {32, 32});
    ASSERT_TRUE(v.valid) << t << ": " << v.reason;
    ASSERT_TRUE(v.metrics.count("bytes_per_pixel")) << t;
    double b = metric(v, "bytes_per_pixel");
    if (t == "unsorted")
      EXPECT_EQ(b, 0) << t;  // blends into the output image: nothing of its own
    else
      EXPECT_GT(b, 0) << t;
  }
  auto ht = params("planes", "HT");
  ht["nodes"] = "8";
  EXPECT_EQ(metric(run_case("oit", ht, {32, 32}), "bytes_per_pixel"), 8 * 8 + 4 + 16 + 4);
  EXPECT_EQ(metric(run_case("oit", params("planes", "DP"), {32, 32}), "bytes_per_pixel"), 40);
  EXPECT_EQ(metric(run_case("oit", params("planes", "DDP"), {32, 32}), "bytes_per_pixel"), 64);
}

TEST(PeelCli, AnUndefinedTieRuleExitsTwoListingTheValidOnes) {
  auto r = run_oitbench({"run", "oit", "--set", "technique=DP", "--set", "tie_rule=colour", "--quick"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("depth-colour"), std::string::npos) << r.err;
  auto m = run_oitbench({"run", "oit", "--set", "technique=DDP", "--set", "max_layers=-1", "--quick"});
  EXPECT_EQ(m.exit_code, 2) << m.err;
  auto s = run_oitbench({"run", "oit", "--set", "technique=HT", "--set", "max_layers=4", "--quick"});
  EXPECT_EQ(s.exit_code, 2) << "max_layers is DP's and DDP's only: " << s.err;
}

}  // namespace oitbench::test
