// --shard: parsing (I/N, auto from Slurm, Kubernetes and GitLab variables, bad input) and, for every
// shipped preset and N = 1..8, that the shards are disjoint, their union is the whole grid, and no
// interleaved group (with the baseline its speedups pair with) is split. No GL: the plan only.
#include "core/shard.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>

#include "core/plan.hpp"
#include "core/presets.hpp"
#include "experiments/experiments.hpp"

namespace oitbench {
namespace {

EnvLookup env_of(const std::map<std::string, std::string>& vars) {
  return [vars](const char* name) -> const char* {
    auto it = vars.find(name);
    return it == vars.end() ? nullptr : it->second.c_str();
  };
}

std::string usage_error(const std::string& text, const std::map<std::string, std::string>& vars = {}) {
  try {
    parse_shard(text, env_of(vars));
  } catch (const UsageError& e) {
    return e.what();
  }
  return "";
}

TEST(Shard, ParsesIOverN) {
  auto s = parse_shard("2/4", env_of({}));
  EXPECT_EQ(s.index, 2);
  EXPECT_EQ(s.count, 4);
  EXPECT_EQ(s.text(), "2/4");
  EXPECT_TRUE(s.source.empty());
  EXPECT_EQ(parse_shard("1/1", env_of({})).text(), "1/1");
  EXPECT_EQ(ShardSpec{}.text(), "");
}

TEST(Shard, BadValuesNameTheOptionAndWhatIsValid) {
  for (const char* bad : {"0/4", "5/4", "a/b", "4", "/4", "1/", "1/0", "-1/4", "2/4x", " 2/4", "1/100001", ""}) {
    const std::string e = usage_error(bad);
    EXPECT_NE(e.find("--shard"), std::string::npos) << bad << ": " << e;
    EXPECT_NE(e.find("1 <= I <= N"), std::string::npos) << bad << ": " << e;
  }
  const std::string none = usage_error("auto");
  EXPECT_NE(none.find("--shard auto: no scheduler's variables"), std::string::npos) << none;
  EXPECT_NE(none.find("SLURM_ARRAY_TASK_ID"), std::string::npos) << none;
}

TEST(Shard, AutoFromASlurmArray) {
  // --array=0-3: task 2 is shard 3 of 4; --array=1-4: task 1 is shard 1; --array=0-6:2: task 4 is shard 3.
  auto s = parse_shard("auto", env_of({{"SLURM_ARRAY_TASK_ID", "2"},
                                       {"SLURM_ARRAY_TASK_MIN", "0"},
                                       {"SLURM_ARRAY_TASK_MAX", "3"},
                                       {"SLURM_ARRAY_TASK_COUNT", "4"}}));
  EXPECT_EQ(s.text(), "3/4");
  EXPECT_NE(s.source.find("Slurm"), std::string::npos);
  EXPECT_EQ(parse_shard(
                "auto",
                env_of({{"SLURM_ARRAY_TASK_ID", "1"}, {"SLURM_ARRAY_TASK_MIN", "1"}, {"SLURM_ARRAY_TASK_COUNT", "4"}}))
                .text(),
            "1/4");
  EXPECT_EQ(parse_shard("auto", env_of({{"SLURM_ARRAY_TASK_ID", "4"},
                                        {"SLURM_ARRAY_TASK_MIN", "0"},
                                        {"SLURM_ARRAY_TASK_MAX", "6"},
                                        {"SLURM_ARRAY_TASK_STEP", "2"},
                                        {"SLURM_ARRAY_TASK_COUNT", "4"}}))
                .text(),
            "3/4");
  // --array=1,3,10: no arithmetic from the IDs to 1..N.
  const std::string e = usage_error("auto", {{"SLURM_ARRAY_TASK_ID", "3"},
                                             {"SLURM_ARRAY_TASK_MIN", "1"},
                                             {"SLURM_ARRAY_TASK_MAX", "10"},
                                             {"SLURM_ARRAY_TASK_COUNT", "3"}});
  EXPECT_NE(e.find("not a range"), std::string::npos) << e;
  EXPECT_NE(usage_error("auto", {{"SLURM_ARRAY_TASK_ID", "3"}}).find("SLURM_ARRAY_TASK_MIN is not set"),
            std::string::npos);
  EXPECT_NE(usage_error("auto", {{"SLURM_ARRAY_TASK_ID", "x"}}).find("not a whole number"), std::string::npos);
}

TEST(Shard, AutoFromAKubernetesIndexedJob) {
  auto s = parse_shard("auto", env_of({{"JOB_COMPLETION_INDEX", "0"}, {"OITBENCH_SHARD_COUNT", "4"}}));
  EXPECT_EQ(s.text(), "1/4");
  EXPECT_NE(s.source.find("Kubernetes"), std::string::npos);
  EXPECT_EQ(parse_shard("auto", env_of({{"JOB_COMPLETION_INDEX", "3"}, {"OITBENCH_SHARD_COUNT", "4"}})).text(), "4/4");
  EXPECT_NE(usage_error("auto", {{"JOB_COMPLETION_INDEX", "4"}, {"OITBENCH_SHARD_COUNT", "4"}}).find("5 of 4"),
            std::string::npos);
  EXPECT_NE(usage_error("auto", {{"JOB_COMPLETION_INDEX", "1"}}).find("OITBENCH_SHARD_COUNT is not set"),
            std::string::npos);
}

TEST(Shard, AutoFromGitLabParallel) {
  auto s = parse_shard("auto", env_of({{"CI_NODE_INDEX", "1"}, {"CI_NODE_TOTAL", "3"}}));
  EXPECT_EQ(s.text(), "1/3");  // CI_NODE_INDEX is 1-based
  EXPECT_NE(s.source.find("GitLab"), std::string::npos);
  EXPECT_EQ(parse_shard("auto", env_of({{"CI_NODE_INDEX", "3"}, {"CI_NODE_TOTAL", "3"}})).text(), "3/3");
  EXPECT_NE(usage_error("auto", {{"CI_NODE_INDEX", "0"}, {"CI_NODE_TOTAL", "3"}}).find("0 of 3"), std::string::npos);
  EXPECT_NE(usage_error("auto", {{"CI_NODE_INDEX", "2"}}).find("CI_NODE_TOTAL is not set"), std::string::npos);
}

TEST(Shard, AssignsUnitsToTheLeastLoadedShard) {
  EXPECT_EQ(assign_shards({8, 2, 1, 1, 8}, 2), (std::vector<int>{0, 1, 1, 1, 1}));
  EXPECT_EQ(assign_shards({1, 1, 1}, 4), (std::vector<int>{0, 1, 2}));
}

// A unit's identity: its plan entry and its cases' keys with their pairing.
std::string unit_text(const std::vector<Planned>& plan, const RunUnit& u) {
  std::string s = std::to_string(u.planned) + (u.isolated ? " isolated" : "");
  for (size_t i = 0; i < u.group.cases.size(); ++i)
    s += " | " + case_key(plan[u.planned].exp->name(), plan[u.planned].res, u.group.cases[i]) +
         (u.group.shadow[i] ? " shadow" : "") + " base " + std::to_string(u.group.baseline_of[i]);
  return s;
}

// What the test checks of N shards against the whole plan; empty when they are right, else what is wrong.
std::string check_shards(const std::vector<Planned>& plan, const std::vector<RunUnit>& whole,
                         const std::vector<std::vector<RunUnit>>& shards) {
  std::multiset<std::string> expected, got;  // units, whole: no group split, each once
  std::multiset<std::string> rows_expected, rows_got;
  auto rows = [&](const RunUnit& u, std::multiset<std::string>& into) {
    for (size_t i = 0; i < u.group.cases.size(); ++i)
      if (!u.group.shadow[i])
        into.insert(std::to_string(u.planned) + " " +
                    case_key(plan[u.planned].exp->name(), plan[u.planned].res, u.group.cases[i]));
  };
  for (const auto& u : whole) {
    expected.insert(unit_text(plan, u));
    rows(u, rows_expected);
  }
  for (const auto& s : shards)
    for (const auto& u : s) {
      got.insert(unit_text(plan, u));
      rows(u, rows_got);
    }
  if (rows_got != rows_expected) return "the shards' rows are not the whole grid's, each once";
  if (got != expected) return "a unit of the whole plan is split, missing or run twice";
  // A case with a baseline in its plan entry pairs with it inside its unit.
  for (const auto& s : shards)
    for (const auto& u : s)
      for (size_t i = 0; i < u.group.cases.size(); ++i) {
        const auto& p = plan[u.planned];
        if (u.isolated || p.baseline.empty() || u.group.baseline_of[i] >= 0) continue;
        for (const auto& other : p.grid->cases())
          if (is_baseline_of(other, u.group.cases[i], p.baseline) && p.exp->max_interleave(p.res) > 1)
            return "a case is in a unit without its baseline: " + unit_text(plan, u);
      }
  return "";
}

TEST(Shard, EveryPresetSplitsIntoDisjointCompleteShardsWithoutSplittingAGroup) {
  Registry registry;
  register_all_experiments(registry);
  const auto presets = list_presets(default_preset_dir());
  ASSERT_GE(presets.size(), 10u);
  size_t checked = 0;
  for (const auto& listed : presets) {
    const Preset preset = load_preset(default_preset_dir(), listed.name);
    for (bool hardware : {false, true}) {
      RunOptions options;
      const auto plan = make_plan(registry, preset.runs, options, hardware);
      const auto whole = plan_units(plan, options);
      for (int n = 1; n <= 8; ++n) {
        std::vector<std::vector<RunUnit>> shards;
        for (int i = 1; i <= n; ++i) shards.push_back(plan_units(plan, options, ShardSpec{i, n, ""}));
        EXPECT_EQ(check_shards(plan, whole, shards), "") << preset.name << (hardware ? " hardware" : "") << " N=" << n;
        ++checked;
      }
    }
  }
  EXPECT_EQ(checked, presets.size() * 16);
}

// The check above fails on broken shards: a unit dropped, one run twice, a group split in two.
TEST(Shard, TheCheckFailsOnBrokenShards) {
  Registry registry;
  register_all_experiments(registry);
  const Preset preset = load_preset(default_preset_dir(), "resolve-speedups");
  RunOptions options;
  const auto plan = make_plan(registry, preset.runs, options, false);
  const auto whole = plan_units(plan, options);
  ASSERT_GE(whole.size(), 2u);
  std::vector<std::vector<RunUnit>> shards = {plan_units(plan, options, {1, 2, ""}),
                                              plan_units(plan, options, {2, 2, ""})};
  ASSERT_EQ(check_shards(plan, whole, shards), "");
  auto dropped = shards;
  dropped[1].pop_back();
  EXPECT_NE(check_shards(plan, whole, dropped), "");
  auto twice = shards;
  twice[1].push_back(shards[0].front());
  EXPECT_NE(check_shards(plan, whole, twice), "");
  // A group with a baseline cut in two: the baseline and its first case in one shard, the rest in another.
  auto split = shards;
  auto paired = std::find_if(split[0].begin(), split[0].end(),
                             [](const RunUnit& u) { return u.group.cases.size() >= 3 && u.group.baseline_of[1] == 0; });
  ASSERT_NE(paired, split[0].end());
  RunUnit& g = *paired;
  RunUnit rest = g;
  rest.group.cases.erase(rest.group.cases.begin(), rest.group.cases.begin() + 2);
  rest.group.baseline_of.assign(rest.group.cases.size(), -1);
  rest.group.shadow.assign(rest.group.cases.size(), false);
  g.group.cases.resize(2);
  g.group.baseline_of.resize(2);
  g.group.shadow.resize(2);
  split[1].push_back(rest);
  EXPECT_NE(check_shards(plan, whole, split), "");
}

}  // namespace
}  // namespace oitbench
