// oit's MBOIT and STOCHASTIC (micro/oit/moments/moments.hpp): every variant matches its CPU model, each
// validator fails on a wrong result, the error is data that behaves as the papers say (more
// moments, more samples: less error), STOCHASTIC is exact where alpha is 0 or 1 and flickers
// across frames, and values the techniques do not define are usage errors (exit 2).
#include "oit/moments/moments.hpp"

#include "support/test_support.hpp"

namespace oitbench::test {

class Moments : public GlTest {};

namespace {
std::map<std::string, std::string> mboit(const std::string& scene, const std::string& moments,
                                         const std::string& kind = "power", const std::string& bits = "32") {
  return {{"scene", scene},     {"view", "rev"},       {"technique", "MBOIT"}, {"detail", "small"},
          {"moments", moments}, {"moment_kind", kind}, {"moment_bits", bits},  {"flicker_runs", "2"}};
}
std::map<std::string, std::string> stochastic(const std::string& scene, const std::string& samples) {
  return {{"scene", scene},
          {"view", "fwd"},
          {"technique", "STOCHASTIC"},
          {"detail", "small"},
          {"samples_per_pixel", samples},
          {"flicker_runs", "3"}};
}
double metric(const Validation& v, const std::string& name) { return std::stod(v.metrics.at(name)); }
}  // namespace

TEST_F(Moments, EveryMboitVariantMatchesItsModel) {
  for (const char* kind : {"power", "trigonometric"})
    for (const char* bits : {"32", "16"})
      for (const char* n : {"4", "6", "8"}) {
        auto v = run_case("oit", mboit("hairball", n, kind, bits), {40, 24});
        EXPECT_TRUE(v.valid) << kind << " " << n << " " << bits << ": " << v.reason;
        EXPECT_EQ(v.metrics.at("nonfinite"), "0");
        EXPECT_GT(metric(v, "rmse"), 0.0) << "an approximation on 24 layers";
        EXPECT_EQ(v.metrics.at("flicker_pixels"), "0") << "MBOIT is order-independent and deterministic";
        // b0 and n moments, 4 or 2 bytes each, plus the RGBA32F weighted colour.
        EXPECT_EQ(std::stoi(v.metrics.at("bytes_per_pixel")), (1 + std::stoi(n)) * std::stoi(bits) / 8 + 16);
      }
}

TEST_F(Moments, MboitErrorFallsFromFourToEightPowerMoments) {
  auto four = run_case("oit", mboit("planes", "4"), {32, 32});
  auto eight = run_case("oit", mboit("planes", "8"), {32, 32});
  ASSERT_TRUE(four.valid && eight.valid) << four.reason << eight.reason;
  EXPECT_GT(metric(four, "rmse"), metric(eight, "rmse"));
}

TEST_F(Moments, StochasticMatchesItsModelForEverySampleCount) {
  for (const char* n : {"4", "8", "16"}) {
    auto v = run_case("oit", stochastic("hairball", n), {40, 24});
    EXPECT_TRUE(v.valid) << n << ": " << v.reason;
    int msaa = std::stoi(v.metrics.at("msaa_samples"));
    EXPECT_EQ(std::stoi(n) % msaa, 0);
    EXPECT_EQ(std::stoi(v.metrics.at("bytes_per_pixel")), msaa * 20 + 4);
    EXPECT_GT(std::stoi(v.metrics.at("flicker_pixels")), 0) << n << ": the seed changes every frame";
  }
}

TEST_F(Moments, StochasticErrorFallsWithTheSampleCount) {
  auto four = run_case("oit", stochastic("planes", "4"), {48, 48});
  auto sixteen = run_case("oit", stochastic("planes", "16"), {48, 48});
  ASSERT_TRUE(four.valid && sixteen.valid) << four.reason << sixteen.reason;
  EXPECT_GT(metric(four, "rmse"), metric(sixteen, "rmse"));
}

TEST_F(Moments, StochasticIsExactWhereAlphaIsZeroOrOne) {
  auto p = stochastic(std::string(OITBENCH_TEST_DATA) + "/stochastic_binary_alpha.json", "4");
  p.erase("detail");
  auto v = run_case("oit", p, {32, 32});
  ASSERT_TRUE(v.valid) << v.reason;
  EXPECT_LE(metric(v, "max_abs_error"), 1e-6);
  EXPECT_EQ(v.metrics.at("flicker_pixels"), "0");
}

TEST_F(Moments, FiniteAndValidOnTheNumericallyHardScenes) {
  for (const char* scene : {"hard_opaque_front", "hard_opaque_middle", "hard_alpha_zero", "hard_equal_depth",
                            "hard_near_far", "hard_sparse"}) {
    std::string path = std::string(OITBENCH_TEST_DATA) + "/" + scene + ".json";
    auto m = mboit(path, "6");
    auto t = mboit(path, "8", "trigonometric", "16");
    auto st = stochastic(path, "8");
    for (auto* p : {&m, &t, &st}) {
      (*p)["view"] = "fwd";
      p->erase("detail");
      auto v = run_case("oit", *p, {32, 32});
      EXPECT_TRUE(v.valid) << scene << " " << p->at("technique") << ": " << v.reason;
      EXPECT_EQ(v.metrics.at("nonfinite"), "0") << scene << " " << p->at("technique");
    }
  }
}

TEST_F(Moments, EachValidatorFailsOnAWrongResult) {
  auto m = mboit("hairball", "6");
  m["fault"] = "wrong-result";
  auto s = stochastic("hairball", "4");
  s["fault"] = "wrong-result";
  for (const auto& p : {m, s}) {
    auto v = run_case("oit", p, {32, 32});
    EXPECT_FALSE(v.valid) << p.at("technique");
    EXPECT_NE(v.reason.find("CPU model"), std::string::npos) << v.reason;
  }
}

TEST_F(Moments, UndefinedValuesAreUsageErrorsListingTheValidOnes) {
  struct Bad {
    std::string set, valid;
  };
  for (const Bad& b : {Bad{"moments=5", "4|6|8"}, Bad{"samples_per_pixel=3", "4|8|16"},
                       Bad{"moment_kind=nosuch", "power|trigonometric"}, Bad{"moment_bits=24", "32|16"}}) {
    std::string technique = b.set.rfind("samples", 0) == 0 ? "STOCHASTIC" : "MBOIT";
    auto r = run_oitbench({"run", "oit", "--quick", "--set", "technique=" + technique, "--set", b.set, "--out", "-"});
    EXPECT_EQ(r.exit_code, 2) << b.set << ": " << r.err;
    EXPECT_NE(r.err.find(b.valid), std::string::npos) << b.set << ": " << r.err;
  }
}

}  // namespace oitbench::test
