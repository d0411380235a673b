// Self-shadowing (micro/oit/scene/shadow_map.cpp) on the small hairball lit by a spot light
// (tests/data/shadow_hairball.json): the opacity map matches the CPU map of the same slices and its
// primitive sort a stable CPU sort, a map drawn one slice off is caught, the map's error against the
// deep shadow map falls as the slices grow (deterministic, so a correctness property), and the
// shadow passes appear as rows only where the scene declares the effect.
#include <set>
#include <string>

#include "support/test_support.hpp"

namespace oitbench::test {

class SelfShadowing : public GlTest {};

namespace {

std::string data(const std::string& name) { return std::string(OITBENCH_TEST_DATA) + "/" + name + ".json"; }

std::map<std::string, std::string> params(const std::string& technique, int slices) {
  return {{"scene", data("shadow_hairball")},
          {"view", "fwd"},
          {"technique", technique},
          {"detail", "small"},
          {"shadow_slices", std::to_string(slices)},
          {"shadow_resolution", "64"},
          {"nodes", "4"}};
}

double metric(const Validation& v, const std::string& name) { return std::stod(v.metrics.at(name)); }

}  // namespace

TEST_F(SelfShadowing, MapMatchesTheCpuMapAndItsErrorFallsWithTheSlices) {
  double previous = 0;
  for (int slices : {8, 64}) {
    auto v = run_case("oit", params("BASE-IS", slices), {48, 48});
    ASSERT_TRUE(v.valid) << slices << " slices: " << v.reason;
    EXPECT_GT(std::stoll(v.metrics.at("shadow_light_fragments")), 1000);
    EXPECT_LE(metric(v, "shadow_map_max_diff"), 1e-2);
    const double rmse = metric(v, "shadow_rmse");
    EXPECT_GT(rmse, 0.0) << "an opacity map approximates the deep shadow map";
    if (slices == 64) {
      EXPECT_LT(rmse, 0.8 * previous) << "64 slices: " << rmse << ", 8 slices: " << previous;
    }
    previous = rmse;
  }
}

TEST_F(SelfShadowing, ApproximateTechniquesShadeTheSameWay) {
  for (const char* t : {"WBOIT", "MLAB"}) {
    auto v = run_case("oit", params(t, 16), {48, 48});
    EXPECT_TRUE(v.valid) << t << ": " << v.reason;
    EXPECT_TRUE(v.metrics.count("shadow_rmse")) << t;
  }
}

TEST_F(SelfShadowing, AMapOneSliceOffIsInvalid) {
  auto p = params("BASE-IS", 16);
  p["fault"] = "shadow-slice-off";
  auto v = run_case("oit", p, {48, 48});
  EXPECT_FALSE(v.valid);
  EXPECT_NE(v.reason.find("shadow-map:"), std::string::npos) << v.reason;
  // The sort's own validator fails on a broken split (the lines experiment's wrong-result hook).
  p["fault"] = "wrong-result";  // breaks the resolve too: the reason must name the sort as well
  auto s = run_case("oit", p, {48, 48});
  EXPECT_FALSE(s.valid);
  EXPECT_NE(s.reason.find("shadow-sort:"), std::string::npos) << s.reason;
}

TEST_F(SelfShadowing, ShadowPassRowsOnlyWhereTheSceneDeclaresTheEffect) {
  auto out = temp_dir("shadow") / "rows.csv";
  auto r = run_oitbench({"run",          "oit",
                         "--set",        "scene=" + data("shadow_hairball") + "," + data("hard_sparse"),
                         "--set",        "view=fwd",
                         "--set",        "technique=BASE-IS",
                         "--set",        "detail=small",
                         "--set",        "shadow_slices=8",
                         "--set",        "shadow_resolution=32",
                         "--resolution", "32x32",
                         "--reps",       "1",
                         "--out",        out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::map<std::string, std::set<std::string>> passes;
  for (const auto& row : read_csv_rows(out)) {
    EXPECT_EQ(row.at("valid"), "1") << row.at("scene") << " " << row.at("pass");
    passes[row.at("scene")].insert(row.at("pass"));
  }
  const auto& lit = passes[data("shadow_hairball")];
  EXPECT_TRUE(lit.count("shadow-sort") && lit.count("shadow-map"));
  const auto& unlit = passes[data("hard_sparse")];
  EXPECT_FALSE(unlit.empty());
  EXPECT_FALSE(unlit.count("shadow-sort") || unlit.count("shadow-map"));
}

}  // namespace oitbench::test
