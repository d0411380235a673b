// oit's SLAB (micro/oit/slab/slab.hpp): every layer count matches its CPU model (same masks, same
// insertions), its validator fails on a wrong result, layers as many as the samples never merge (so
// more layers change nothing), opaque and invisible fragments are exact, the seed changes the
// masks every frame (flicker), and values SLAB does not define are usage errors (exit 2).
#include "oit/slab/slab.hpp"

#include "support/test_support.hpp"

namespace oitbench::test {

class Slab : public GlTest {};

namespace {
std::map<std::string, std::string> slab(const std::string& scene, const std::string& layers,
                                        const std::string& samples) {
  return {{"scene", scene},     {"view", "fwd"},         {"technique", "SLAB"},
          {"detail", "small"},  {"slab_layers", layers}, {"samples_per_pixel", samples},
          {"flicker_runs", "3"}};
}
double metric(const Validation& v, const std::string& name) { return std::stod(v.metrics.at(name)); }
}  // namespace

TEST_F(Slab, EveryLayerCountMatchesItsModelOnHairball) {
  for (const char* k : {"1", "2", "4", "8"}) {
    auto v = run_case("oit", slab("hairball", k, "8"), {40, 24});
    EXPECT_TRUE(v.valid) << k << ": " << v.reason;
    EXPECT_EQ(v.metrics.at("nonfinite"), "0");
    EXPECT_EQ(v.metrics.at("capped_updates"), "0");
    EXPECT_GT(metric(v, "rmse"), 0.0) << "an approximation on 24 layers";
    EXPECT_EQ(std::stoi(v.metrics.at("bytes_per_pixel")), std::stoi(k) * 12 + 4);
    EXPECT_GT(std::stoi(v.metrics.at("flicker_pixels")), 0) << k << ": the seed changes every frame";
  }
}

TEST_F(Slab, EverySampleCountMatchesItsModelOnPlanes) {
  for (const char* s : {"4", "16", "32"}) {
    auto v = run_case("oit", slab("planes", "2", s), {64, 64});
    EXPECT_TRUE(v.valid) << s << ": " << v.reason;
  }
}

TEST_F(Slab, AsManyLayersAsSamplesNeverMerge) {
  // The masks are disjoint and never empty, so 4 samples fill at most 4 layers: 8 change nothing.
  auto four = run_case("oit", slab("hairball", "4", "4"), {40, 24});
  auto eight = run_case("oit", slab("hairball", "8", "4"), {40, 24});
  ASSERT_TRUE(four.valid && eight.valid) << four.reason << eight.reason;
  EXPECT_EQ(four.metrics.at("rmse"), eight.metrics.at("rmse"));
  EXPECT_EQ(four.metrics.at("max_abs_error"), eight.metrics.at("max_abs_error"));
}

TEST_F(Slab, ExactWhereAlphaIsZeroOrOne) {
  auto p = slab(std::string(OITBENCH_TEST_DATA) + "/stochastic_binary_alpha.json", "1", "4");
  p.erase("detail");
  auto v = run_case("oit", p, {32, 32});
  ASSERT_TRUE(v.valid) << v.reason;
  EXPECT_LE(metric(v, "max_abs_error"), 1e-6);
  EXPECT_EQ(v.metrics.at("flicker_pixels"), "0");
}

TEST_F(Slab, TheValidatorFailsOnAWrongResult) {
  auto p = slab("hairball", "2", "8");
  p["fault"] = "wrong-result";
  auto v = run_case("oit", p, {32, 32});
  EXPECT_FALSE(v.valid);
  EXPECT_NE(v.reason.find("SLAB's CPU model"), std::string::npos) << v.reason;
}

TEST_F(Slab, UndefinedLayerCountsAreUsageErrorsListingTheValidOnes) {
  auto r = run_oitbench({"run", "oit", "--quick", "--set", "technique=SLAB", "--set", "slab_layers=3", "--out", "-"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("1|2|4|8"), std::string::npos) << r.err;
}

}  // namespace oitbench::test
