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
