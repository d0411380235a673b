// oit's WOIT (micro/oit/wavelets/wavelets.hpp): every variant matches its CPU model on small scenes,
// the validator fails on a wrong result, more coefficients give less error, the Haar helpers
// reconstruct what they project, and values the technique does not define are usage errors.
#include "oit/wavelets/wavelet_model.hpp"
#include "support/test_support.hpp"

namespace oitbench::test {

class Wavelets : public GlTest {};

namespace {
std::map<std::string, std::string> woit(const std::string& scene, const std::string& coeffs,
                                        const std::string& bits = "32", const std::string& basis = "haar") {
  return {{"scene", scene},           {"view", "fwd"},        {"technique", "WOIT"},    {"detail", "small"},
          {"wavelet_coeffs", coeffs}, {"wavelet_bits", bits}, {"wavelet_basis", basis}, {"flicker_runs", "2"}};
}
double metric(const Validation& v, const std::string& name) { return std::stod(v.metrics.at(name)); }
}  // namespace

TEST(WaveletMath, HaarAbsorbanceIsTheStepFunctionSmoothedOverOneCell) {
  using oit::haar_absorbance;
  using oit::haar_contribution;
  for (int n : {8, 16, 32}) {
    // Two pulses, 0.7 at x = 0.3 and 1.2 at x = 0.81: sum their coefficients.
    std::vector<double> a(n), b(n), c(n);
    haar_contribution(0.3, 0.7, n, a.data());
    haar_contribution(0.81, 1.2, n, b.data());
    for (int i = 0; i < n; ++i) c[i] = a[i] + b[i];
    const double cell = 1.0 / n;
    EXPECT_NEAR(haar_absorbance(c.data(), n, 0.0), 0.0, 1e-12) << n;
    EXPECT_NEAR(haar_absorbance(c.data(), n, 0.999999), 1.9, 1e-5) << n;
    // Outside the pulses' cells the absorbance in front is exact.
    double after_first = (std::floor(0.3 / cell) + 1) * cell;
    EXPECT_NEAR(haar_absorbance(c.data(), n, after_first + 1e-9), 0.7, 1e-6) << n;
    EXPECT_NEAR(haar_absorbance(c.data(), n, std::floor(0.3 / cell) * cell - 1e-9), 0.0, 1e-6) << n;
    // Inside a pulse's cell it rises linearly.
    double mid = (std::floor(0.81 / cell) + 0.5) * cell;
    EXPECT_NEAR(haar_absorbance(c.data(), n, mid), 0.7 + 0.6, 1e-6) << n;
  }
}

TEST_F(Wavelets, EveryVariantMatchesItsModel) {
  for (const char* basis : {"haar", "cosine"})
    for (const char* scene : {"planes", "hairball"})
      for (const char* bits : {"32", "16"})
        for (const char* n : {"8", "16", "32"}) {
          auto v = run_case("oit", woit(scene, n, bits, basis), {40, 24});
          EXPECT_TRUE(v.valid) << basis << " " << scene << " " << n << " " << bits << ": " << v.reason;
          EXPECT_EQ(v.metrics.at("nonfinite"), "0");
          EXPECT_GT(metric(v, "rmse"), 0.0) << "an approximation";
          EXPECT_EQ(v.metrics.at("flicker_pixels"), "0") << "WOIT is order-independent and deterministic";
          EXPECT_EQ(std::stoi(v.metrics.at("bytes_per_pixel")), std::stoi(n) * std::stoi(bits) / 8 + 16);
          // With the blender's half rounding probed, the model reproduces the 16-bit sums too.
          EXPECT_LT(metric(v, "model_max_diff"), 1e-4) << basis << " " << scene << " " << n << " " << bits;
          if (std::string(bits) == "16") {
            EXPECT_TRUE(v.metrics.count("half_blend_rounding"));
          }
        }
}

TEST_F(Wavelets, ErrorFallsFromEightToThirtyTwoCoefficients) {
  auto eight = run_case("oit", woit("hairball", "8"), {48, 48});
  auto many = run_case("oit", woit("hairball", "32"), {48, 48});
  ASSERT_TRUE(eight.valid && many.valid) << eight.reason << many.reason;
  EXPECT_GT(metric(eight, "rmse"), metric(many, "rmse"));
}

TEST_F(Wavelets, FiniteAndValidOnTheNumericallyHardScenes) {
  for (const char* scene : {"hard_opaque_front", "hard_opaque_middle", "hard_alpha_zero", "hard_equal_depth",
                            "hard_near_far", "hard_sparse"})
    for (const char* bits : {"32", "16"}) {
      auto p = woit(std::string(OITBENCH_TEST_DATA) + "/" + scene + ".json", "32", bits);
      p.erase("detail");
      auto v = run_case("oit", p, {32, 32});
      EXPECT_TRUE(v.valid) << scene << " " << bits << ": " << v.reason;
      EXPECT_EQ(v.metrics.at("nonfinite"), "0") << scene;
    }
}

TEST_F(Wavelets, TheValidatorFailsOnAWrongResult) {
  for (const char* basis : {"haar", "cosine"}) {
    auto p = woit("hairball", "16", "32", basis);
    p["fault"] = "wrong-result";
    auto v = run_case("oit", p, {32, 32});
    EXPECT_FALSE(v.valid) << basis;
    EXPECT_NE(v.reason.find("CPU model"), std::string::npos) << v.reason;
  }
}

TEST(WaveletMath, CosineAbsorbanceApproachesTheStepAndStaysInItsRange) {
  using oit::cosine_absorbance;
  using oit::cosine_contribution;
  std::vector<double> c(32);
  cosine_contribution(0.5, 0.9, 32, c.data());
  EXPECT_NEAR(cosine_absorbance(c.data(), 32, 0.0), 0.0, 1e-12);
  EXPECT_NEAR(cosine_absorbance(c.data(), 32, 0.999999), 0.9, 1e-3);
  EXPECT_NEAR(cosine_absorbance(c.data(), 32, 0.5), 0.45, 1e-6);  // half the step at the pulse (symmetry)
  EXPECT_LT(cosine_absorbance(c.data(), 32, 0.3), 0.05);
  EXPECT_GT(cosine_absorbance(c.data(), 32, 0.7), 0.85);
  for (double x = 0; x < 1; x += 0.01) {
    EXPECT_GE(cosine_absorbance(c.data(), 32, x), 0.0);
    EXPECT_LE(cosine_absorbance(c.data(), 32, x), 0.9);
  }
}

TEST_F(Wavelets, UndefinedValuesAreUsageErrorsListingTheValidOnes) {
  struct Bad {
    std::string set, valid;
  };
  for (const Bad& b : {Bad{"wavelet_coeffs=12", "8|16|32"}, Bad{"wavelet_bits=24", "32|16"},
                       Bad{"wavelet_basis=daubechies", "haar|cosine"}}) {
    auto r = run_oitbench({"run", "oit", "--quick", "--set", "technique=WOIT", "--set", b.set, "--out", "-"});
    EXPECT_EQ(r.exit_code, 2) << b.set << ": " << r.err;
    EXPECT_NE(r.err.find(b.valid), std::string::npos) << b.set << ": " << r.err;
  }
}

}  // namespace oitbench::test
