#include "core/params.hpp"

#include <gtest/gtest.h>

#include <regex>

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

namespace {
// The message of the UsageError parse_preset throws for `text`, or "" when it parses.
std::string preset_error(const std::string& text) {
  try {
    parse_preset("t", "t.json", text);
  } catch (const UsageError& e) {
    return e.what();
  }
  return "";
}
std::string entry_with(const std::string& hardware) {
  return "{\"runs\": [{\"experiment\": \"occupancy\", \"hardware\": " + hardware + "}]}";
}
}  // namespace

TEST(Presets, AnEntryMayCarryItsSizesForHardwareDrivers) {
  auto p = parse_preset("t", "t.json", R"({"runs": [
      {"experiment": "occupancy", "resolution": "128x96", "reps": 2,
       "hardware": {"resolution": "1920x1080", "reps": 10, "warmup": 2}},
      {"experiment": "occupancy", "hardware": {"reps": 20}},
      {"experiment": "occupancy"}]})");
  ASSERT_EQ(p.runs.size(), 3u);
  ASSERT_TRUE(p.runs[0].hardware.has_value());
  EXPECT_EQ(p.runs[0].hardware->resolution->width, 1920);
  EXPECT_EQ(p.runs[0].hardware->resolution->height, 1080);
  EXPECT_EQ(*p.runs[0].hardware->reps, 10);
  EXPECT_EQ(*p.runs[0].hardware->warmup, 2);
  EXPECT_EQ(p.runs[0].resolution->width, 128);  // the software size stays the entry's own
  EXPECT_FALSE(p.runs[1].hardware->resolution.has_value());
  EXPECT_EQ(*p.runs[1].hardware->reps, 20);
  EXPECT_FALSE(p.runs[2].hardware.has_value());
}

TEST(Presets, MalformedHardwareSizesNameFileLineColumnAndEntry) {
  // The place: runs[1]'s "reps" inside "hardware", line 5 column 44.
  EXPECT_EQ(preset_error("{\n"
                         "  \"runs\": [\n"
                         "    {\"experiment\": \"occupancy\", \"hardware\": {\"reps\": 3}},\n"
                         "    {\"experiment\": \"occupancy\",\n"
                         "     \"hardware\": {\"resolution\": \"800x600\", \"reps\": \"ten\"}}\n"
                         "  ]\n"
                         "}\n"),
            "t.json:5:44: runs[1].hardware.reps: expected a positive integer (at most 100000), got \"ten\"");
  EXPECT_EQ(preset_error(entry_with(R"({"reps": 0})")),
            "t.json:1:52: runs[0].hardware.reps: expected a positive integer (at most 100000), got 0");
  EXPECT_EQ(preset_error(entry_with(R"({"warmup": -1})")),
            "t.json:1:52: runs[0].hardware.warmup: expected a non-negative integer (at most 100000), got -1");
  EXPECT_EQ(preset_error(entry_with(R"({"resolution": "1920by1080"})")),
            "t.json:1:52: runs[0].hardware.resolution: resolution '1920by1080': expected WIDTHxHEIGHT, e.g. 800x600");
  EXPECT_EQ(preset_error(entry_with(R"({"resolution": 1920})")),
            "t.json:1:52: runs[0].hardware.resolution: expected \"WIDTHxHEIGHT\", got number");
  EXPECT_EQ(preset_error(entry_with(R"({"resolution": "0x1080"})")),
            "t.json:1:52: runs[0].hardware.resolution: resolution '0x1080': each side must be in [1, 16384]");
  EXPECT_EQ(preset_error(entry_with(R"({"size": "1920x1080"})")),
            "t.json:1:52: runs[0].hardware.size: unknown key \"size\"; expected resolution, reps, warmup, set");
  EXPECT_EQ(preset_error(entry_with(R"("1920x1080")")),
            "t.json:1:39: runs[0].hardware: expected an object with one or more of resolution, reps, warmup, set "
            "(what changes on hardware drivers), got string");
  EXPECT_EQ(preset_error(entry_with("{}")),
            "t.json:1:39: runs[0].hardware: expected an object with one or more of resolution, reps, warmup, set "
            "(what changes on hardware drivers), got {}");
  // The entry's own keys are placed the same way now.
  EXPECT_EQ(preset_error(R"({"runs": [{"experiment": "occupancy", "sett": {}}]})"),
            "t.json:1:39: runs[0].sett: unknown key \"sett\"; expected experiment, set, resolution, reps, warmup, "
            "quick, hardware, baseline");
  EXPECT_EQ(preset_error(R"({"runs": [{"experiment": "occupancy", "baseline": []}]})"),
            "t.json:1:39: runs[0].baseline: expected an object of parameter values");
  EXPECT_EQ(preset_error(R"({"runs": [{"experiment": "occupancy", "reps": 1.5}]})"),
            "t.json:1:39: runs[0].reps: expected a positive integer (at most 100000), got 1.5");
  EXPECT_EQ(preset_error(R"({"runs": [{"experiment": "occupancy", "set": {"size": [1, {}]}}]})"),
            "t.json:1:59: runs[0].set.size[1]: expected a string or a number, got object");
  EXPECT_EQ(preset_error(R"({"runs": [], "x": 1})"), "t.json:1:14: x: unknown key \"x\"; expected description, runs");
}

TEST(Presets, HardwareSizesApplyOnlyOnHardwareDriversAndTheCommandLineWins) {
  Registry registry;
  register_all_experiments(registry);
  const Experiment& occ = *registry.find("occupancy");  // 800x600, --quick 200x150
  RunRequest r{"occupancy", {}, Resolution{128, 96}, 2, 1};
  r.hardware = HardwareSizes{Resolution{1920, 1080}, 10, 2};
  const RunOptions none;
  auto sw = resolve_run_size(r, occ, none, false);
  EXPECT_EQ(sw.resolution.width, 128);
  EXPECT_EQ(sw.reps, 2);
  EXPECT_EQ(sw.warmup, 1);
  EXPECT_FALSE(sw.hardware_sizes);
  auto hw = resolve_run_size(r, occ, none, true);
  EXPECT_EQ(hw.resolution.width, 1920);
  EXPECT_EQ(hw.resolution.height, 1080);
  EXPECT_EQ(hw.reps, 10);
  EXPECT_EQ(hw.warmup, 2);
  EXPECT_TRUE(hw.hardware_sizes);
  // --resolution and --reps win; the warm-up not given keeps the hardware one.
  RunOptions cli;
  cli.resolution = Resolution{64, 48};
  cli.reps = 3;
  cli.reps_given = true;
  auto won = resolve_run_size(r, occ, cli, true);
  EXPECT_EQ(won.resolution.width, 64);
  EXPECT_EQ(won.reps, 3);
  EXPECT_EQ(won.warmup, 2);
  EXPECT_TRUE(won.hardware_sizes);
  cli.warmup = 0;
  cli.warmup_given = true;
  EXPECT_FALSE(resolve_run_size(r, occ, cli, true).hardware_sizes);
  // A partial hardware entry replaces what it names and keeps the entry's own for the rest.
  r.hardware = HardwareSizes{std::nullopt, 20, std::nullopt};
  hw = resolve_run_size(r, occ, none, true);
  EXPECT_EQ(hw.resolution.width, 128);
  EXPECT_EQ(hw.reps, 20);
  EXPECT_EQ(hw.warmup, 1);
  // A quick entry: the experiment's quick size and 3 repetitions here, the hardware resolution there.
  RunRequest q{"occupancy", {}, {}, {}, {}, true, HardwareSizes{Resolution{800, 600}, {}, {}}};
  sw = resolve_run_size(q, occ, none, false);
  EXPECT_EQ(sw.resolution.width, 200);
  EXPECT_EQ(sw.reps, 3);
  hw = resolve_run_size(q, occ, none, true);
  EXPECT_EQ(hw.resolution.width, 800);
  EXPECT_EQ(hw.reps, 3);
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

// shadow_slices on a grid that mixes scenes with and without self-shadowing: the scenes without it run
// once (the parameter is unused there), not once per value as identical cases.
TEST(ParamGrid, ShadowParametersDoNotMultiplyScenesWithoutSelfShadowing) {
  Registry registry;
  register_all_experiments(registry);
  const Experiment* oit = registry.find("oit");
  ASSERT_NE(oit, nullptr);
  auto count = [&](const std::vector<std::string>& slices) {
    std::map<std::string, std::vector<std::string>> o = {
        {"technique", {"BASE-IS"}}, {"scene", {"hairball-lit", "planes"}}, {"view", {"fwd"}}};
    if (!slices.empty()) o["shadow_slices"] = slices;
    std::map<std::string, size_t> n;
    for (const auto& c : expand_grid(registry.params_of(*oit), o, false)) {
      ++n[c.get("scene")];
      EXPECT_EQ(c.uses("shadow_slices"), c.get("scene") == "hairball-lit") << c.describe();
    }
    return n;
  };
  auto one = count({}), two = count({"8", "16"});
  EXPECT_GT(one["planes"], 0u);
  EXPECT_EQ(two["planes"], one["planes"]);
  EXPECT_EQ(two["hairball-lit"], 2 * one["hairball-lit"]);
  // Where no selected case holds self-shadowing, the list is a usage error naming the condition.
  try {
    check_requests(registry, {{"oit", {{"scene", {"planes"}}, {"shadow_slices", {"8", "16"}}}, {}, {}, {}}});
    ADD_FAILURE() << "shadow_slices on planes alone was accepted";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("applies only where the case's scene and effects hold self-shadowing"),
              std::string::npos)
        << e.what();
  }
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

TEST(Presets, AHardwareSetReplacesItsListsOnHardwareOnlyAndIsCheckedEverywhere) {
  auto p = parse_preset("t", "t.json", R"({"runs": [{"experiment": "occupancy",
    "set": {"size": [1, 2], "draws": 8}, "hardware": {"set": {"size": [1, 2, 4]}}}]})");
  ASSERT_EQ(p.runs.size(), 1u);
  const RunRequest& r = p.runs[0];
  ASSERT_TRUE(r.hardware);
  EXPECT_EQ(request_overrides(r, false).at("size"), (std::vector<std::string>{"1", "2"}));
  EXPECT_EQ(request_overrides(r, true).at("size"), (std::vector<std::string>{"1", "2", "4"}));
  EXPECT_EQ(request_overrides(r, true).at("draws"), (std::vector<std::string>{"8"}));  // kept
  Registry registry;
  register_all_experiments(registry);
  EXPECT_NO_THROW(check_requests(registry, {r}));
  // A wrong name or value in the hardware set is refused on a software renderer too.
  RunRequest bad = r;
  bad.hardware->set = {{"sise", {"4"}}};
  try {
    check_requests(registry, {bad});
    ADD_FAILURE() << "a hardware set naming no parameter was accepted";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("no parameter 'sise' (in its hardware set)"), std::string::npos) << e.what();
    // The hardware set's own place, not the entry's (runs[0]).
    EXPECT_TRUE(std::regex_search(e.what(), std::regex(R"(^t\.json:2:\d+: runs\[0\]\.hardware\.set: experiment)")))
        << e.what();
  }
  bad.hardware->set = {{"size", {"-3"}}};
  try {
    check_requests(registry, {bad});
    ADD_FAILURE() << "a hardware set with a bad value was accepted";
  } catch (const UsageError& e) {
    EXPECT_TRUE(std::regex_search(e.what(), std::regex(R"(^t\.json:2:\d+: runs\[0\]\.hardware\.set: .*'-3')")))
        << e.what();
  }
  EXPECT_EQ(preset_error(R"({"runs": [{"experiment": "occupancy", "hardware": {"set": {"size": []}}}]})"),
            "t.json:1:60: runs[0].hardware.set.size: empty value list");
  EXPECT_EQ(preset_error(R"({"runs": [{"experiment": "occupancy", "hardware": {"set": 3}}]})"),
            "t.json:1:52: runs[0].hardware.set: expected an object of parameter lists");
}

TEST(Presets, OitInterleavesMoreCasesWhereTheirNodePoolsAreSmall) {
  Registry registry;
  register_all_experiments(registry);
  const Experiment& oit = *registry.find("oit");
  EXPECT_EQ(oit.max_interleave({128, 128}), 8);
  EXPECT_EQ(oit.max_interleave({256, 256}), 8);
  EXPECT_EQ(oit.max_interleave({512, 512}), 4);
  EXPECT_EQ(oit.max_interleave({800, 800}), 2);
  EXPECT_EQ(oit.max_interleave({1920, 1080}), 2);  // a case and its baseline, never fewer
  EXPECT_EQ(oit.max_interleave({16384, 16384}), 2);
}

}  // namespace oitbench
