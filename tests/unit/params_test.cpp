#include "core/params.hpp"

#include <gtest/gtest.h>

#include "core/presets.hpp"
#include "core/runner.hpp"
#include "experiments/experiments.hpp"

namespace oitbench {

TEST(Params, SetOptionListsAndRanges) {
  auto [name, values] = parse_set_option("size=1,2,8..10,16..32:8");
  EXPECT_EQ(name, "size");
  EXPECT_EQ(values, (std::vector<std::string>{"1", "2", "8", "9", "10", "16", "24", "32"}));
  EXPECT_THROW(parse_set_option("size"), UsageError);
  EXPECT_THROW(parse_set_option("=1"), UsageError);
  EXPECT_THROW(parse_set_option("size="), UsageError);
  EXPECT_THROW(parse_set_option("size=9..3"), UsageError);
}

TEST(Params, CartesianProductInSpecOrder) {
  std::vector<ParamSpec> specs = {{"a", "", {"1", "2"}, {"1"}, {}}, {"b", "", {"x", "y", "z"}, {}, {}}};
  auto grid = expand_grid(specs, {}, false);
  ASSERT_EQ(grid.size(), 6u);
  EXPECT_EQ(grid[0].describe(), "a=1 b=x");
  EXPECT_EQ(grid[5].describe(), "a=2 b=z");
  EXPECT_EQ(expand_grid(specs, {}, true).size(), 3u);  // quick grid of a, defaults of b
  EXPECT_EQ(expand_grid(specs, {{"b", {"q"}}}, false).size(), 2u);
}

TEST(Params, ValuesAreCheckedWithTheValidOnesListed) {
  ParamSpec e{"variant", "", {"dynamic"}, {}, {"dynamic", "unrolled"}};
  EXPECT_NO_THROW(e.check("unrolled", "occupancy"));
  try {
    e.check("static", "occupancy");
    FAIL();
  } catch (const UsageError& err) {
    EXPECT_NE(std::string(err.what()).find("valid values: dynamic|unrolled"), std::string::npos);
  }
  ParamSpec n{"size", "", {"1"}, {}, {}, ParamSpec::Kind::Integer, 1, 1024};
  EXPECT_NO_THROW(n.check("1024", "occupancy"));
  EXPECT_THROW(n.check("0", "occupancy"), UsageError);
  EXPECT_THROW(n.check("4.5", "occupancy"), UsageError);
  EXPECT_THROW(n.check("abc", "occupancy"), UsageError);
}

TEST(Params, UnknownExperimentAndParameterNameTheValidOnes) {
  Registry registry;
  register_all_experiments(registry);
  try {
    check_requests(registry, {{"nope", {}, {}, {}, {}}});
    FAIL();
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("occupancy"), std::string::npos) << e.what();
  }
  try {
    check_requests(registry, {{"occupancy", {{"sise", {"1"}}}, {}, {}, {}}});
    FAIL();
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("valid parameters: variant, size"), std::string::npos) << e.what();
  }
}

TEST(Presets, ParsesAndReportsWhereItIsWrong) {
  auto p = parse_preset("t", "t.json", R"({"description": "d", "runs": [
      {"experiment": "occupancy", "set": {"size": [1, 2], "variant": "dynamic"}, "resolution": "64x32", "reps": 2}]})");
  ASSERT_EQ(p.runs.size(), 1u);
  EXPECT_EQ(p.runs[0].overrides.at("size"), (std::vector<std::string>{"1", "2"}));
  EXPECT_EQ(p.runs[0].resolution->height, 32);
  EXPECT_EQ(*p.runs[0].reps, 2);
  try {
    parse_preset("t", "t.json", "{\n  \"runs\": [\n    {\"experiment\": \"occupancy\",,}\n  ]\n}");
    FAIL();
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("t.json:3:"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_preset("t", "t.json", R"({"runs": [{"experiment": "occupancy", "sett": {}}]})"), UsageError);
  EXPECT_THROW(parse_resolution("800by600"), UsageError);
}

}  // namespace oitbench

namespace oitbench {

// Every shipped preset names real experiments and parameters, and every --set in it applies to at
// least one of its cases (a scoped parameter no case uses is a usage error: a preset must not carry one).
TEST(Presets, EveryShippedPresetIsAValidRequestWithScopedParameters) {
  Registry registry;
  register_all_experiments(registry);
  auto presets = list_presets(default_preset_dir());
  ASSERT_GE(presets.size(), 10u);
  for (const auto& p : presets) {
    SCOPED_TRACE(p.name);
    EXPECT_NO_THROW(check_requests(registry, p.runs));
    EXPECT_NO_THROW(check_requests(registry, p.runs, true));
  }
}

TEST(Presets, AScopedSetThatNoCaseUsesIsRejected) {
  Registry registry;
  register_all_experiments(registry);
  try {
    check_requests(registry, {{"oit", {{"technique", {"BASE-IS"}}, {"nodes", {"4"}}}, {}, {}, {}}});
    FAIL() << "nodes with only BASE-IS must be a usage error";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("applies only where technique in {MLAB"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(
      check_requests(registry, {{"oit", {{"technique", {"BASE-IS", "MLAB"}}, {"nodes", {"4"}}}, {}, {}, {}}}));
}

TEST(ParamGrid, ScopedParametersDoNotMultiplyTheCasesTheyDoNotApplyTo) {
  Registry registry;
  register_all_experiments(registry);
  const Experiment* oit = registry.find("oit");
  ASSERT_NE(oit, nullptr);
  auto cases = expand_grid(
      registry.params_of(*oit),
      {{"technique", {"BASE-IS", "MLAB"}}, {"nodes", {"4", "8"}}, {"scene", {"planes"}}, {"view", {"fwd"}}}, false);
  ASSERT_EQ(cases.size(), 3u);  // BASE-IS once, MLAB with 4 and 8
  EXPECT_FALSE(cases[0].uses("nodes"));
  EXPECT_EQ(cases[0].get("nodes"), "8");  // runs at its default, recorded empty
  EXPECT_TRUE(cases[1].uses("nodes"));
  EXPECT_FALSE(cases[1].uses("max_frags"));
}

TEST(ParamGrid, AGridBeyondTheBoundIsRefusedBeforeItIsBuilt) {
  std::vector<ParamSpec> specs;
  std::vector<std::string> values;
  for (int i = 0; i < 1000; ++i) values.push_back(std::to_string(i));
  for (const char* n : {"a", "b"}) {
    ParamSpec s;
    s.name = n;
    s.defaults = values;
    specs.push_back(s);
  }
  EXPECT_THROW(expand_grid(specs, {}, false), UsageError);
}

// A metric named like a parameter, or one that disagrees with another experiment's of the same name,
// fails at registration, not in a CSV.
namespace {
class ClashingExperiment final : public Experiment {
 public:
  explicit ClashingExperiment(std::vector<MetricSpec> m, std::string name = "clash") : m_(std::move(m)), name_(name) {}
  std::string name() const override { return name_; }
  std::string description() const override { return "test"; }
  std::vector<ParamSpec> params() const override {
    ParamSpec p;
    p.name = "depth_param";
    p.defaults = {"1"};
    return {p};
  }
  std::vector<MetricSpec> metric_specs() const override { return m_; }
  std::unique_ptr<CaseInstance> prepare(const ParamSet&, CaseContext&) override { return nullptr; }

 private:
  std::vector<MetricSpec> m_;
  std::string name_;
};
}  // namespace

TEST(Registry, AMetricWithAParametersNameFailsAtRegistration) {
  Registry registry;
  register_all_experiments(registry);
  EXPECT_THROW(
      registry.add(std::make_unique<ClashingExperiment>(std::vector<MetricSpec>{{"seed", ValueType::Integer, "", ""}})),
      std::logic_error);
  EXPECT_THROW(registry.add(std::make_unique<ClashingExperiment>(
                   std::vector<MetricSpec>{{"max_frags", ValueType::Integer, "", ""}})),
               std::logic_error);
  EXPECT_THROW(registry.add(std::make_unique<ClashingExperiment>(
                   std::vector<MetricSpec>{{"median_ms", ValueType::Number, "ms", ""}})),
               std::logic_error);
  EXPECT_THROW(
      registry.add(std::make_unique<ClashingExperiment>(std::vector<MetricSpec>{{"rmse", ValueType::Text, "", ""}})),
      std::logic_error);  // oit's rmse is a number
  EXPECT_NO_THROW(
      registry.add(std::make_unique<ClashingExperiment>(std::vector<MetricSpec>{{"rmse", ValueType::Number, "", ""}})));
}

}  // namespace oitbench
