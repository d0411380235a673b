// The grid walked, never built (core/grid.hpp, core/plan.hpp's UnitStream): the same cases, in the same
// order, as the product the runner used to hold in memory; counted and refused without being built; a
// 2-million-case grid whose first units are made in bounded memory.
#include "core/grid.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>

#include "core/plan.hpp"
#include "core/presets.hpp"
#include "core/runner.hpp"
#include "experiments/experiments.hpp"

namespace oitbench {
namespace {

// The product as the runner built it before the grid was walked (the former expand_grid): every case in
// memory, scoped in spec order, the first of equal cases kept. The reference the walked grid must equal.
std::vector<ParamSet> eager_grid(const std::vector<ParamSpec>& specs,
                                 const std::map<std::string, std::vector<std::string>>& overrides, bool quick) {
  auto values_of = [&](const ParamSpec& spec) -> const std::vector<std::string>& {
    auto it = overrides.find(spec.name);
    return it != overrides.end() ? it->second : (quick && !spec.quick.empty()) ? spec.quick : spec.defaults;
  };
  std::vector<ParamSet> out{ParamSet{}};
  for (const auto& spec : specs) {
    std::vector<ParamSet> next;
    for (const auto& base : out)
      for (const auto& v : values_of(spec)) {
        auto c = base;
        c.set(spec.name, v);
        next.push_back(std::move(c));
      }
    out = std::move(next);
  }
  std::vector<ParamSet> cases;
  std::set<std::vector<std::pair<std::string, std::string>>> seen;
  for (auto& c : out) {
    for (const auto& spec : specs)
      if (!spec.applies(c)) {
        if (!spec.defaults.empty()) c.set(spec.name, spec.defaults.front());
        c.mark_unused(spec.name);
      }
    if (seen.insert(c.used_values()).second) cases.push_back(c);
  }
  return cases;
}

std::string text_of(const std::vector<ParamSet>& cases) {
  std::string s;
  for (const auto& c : cases) {
    for (const auto& [k, v] : c.values()) s += k + "=" + v + (c.uses(k) ? " " : "(unused) ");
    s += "\n";
  }
  return s;
}

ParamSpec spec(std::string name, std::vector<std::string> values) {
  ParamSpec s;
  s.name = std::move(name);
  s.defaults = std::move(values);
  return s;
}

// Scopes that read parameters before and after the scoped one, chains of them, a list with a repeated value,
// an override without the default, and a predicate with and without the parameters it reads declared.
TEST(Grid, WalkedEqualsTheProductHeldInMemory) {
  for (bool declared : {true, false}) {
    std::vector<ParamSpec> s = {spec("a", {"1", "2", "3"}), spec("b", {"x", "y"}), spec("c", {"p", "q", "r"}),
                                spec("d", {"0", "1"}), spec("e", {"u", "v"})};
    s[1].only_when("a", {"2", "3"});  // b: where a is 2 or 3
    s[2].only_when("d", {"1"});       // c: reads a later parameter
    s[3].only_when("b", {"y"});       // d: reads b, itself scoped
    s[4].applies_if = [](const ParamSet& p) { return p.get("a") != "1" || p.get("c") == "q"; };
    if (declared) s[4].applies_if_reads = {"a", "c"};
    for (const auto& o : std::vector<std::map<std::string, std::vector<std::string>>>{
             {}, {{"c", {"r", "p", "r"}}}, {{"a", {"3", "1"}}, {"e", {"v", "u", "v"}}}, {{"b", {"y"}}}}) {
      const CaseGrid grid(s, o, false);
      const auto eager = eager_grid(s, o, false);
      EXPECT_EQ(text_of(grid.cases()), text_of(eager)) << (declared ? "declared" : "undeclared");
      EXPECT_EQ(grid.count(), eager.size());
    }
  }
}

TEST(Grid, EveryPresetsGridWalksLikeTheProductHeldInMemory) {
  Registry registry;
  register_all_experiments(registry);
  size_t grids = 0;
  for (const auto& listed : list_presets(default_preset_dir())) {
    const Preset preset = load_preset(default_preset_dir(), listed.name);
    for (const auto& r : preset.runs)
      for (bool hardware : {false, true}) {
        const auto specs = registry.params_of(*registry.find(r.experiment));
        const auto o = request_overrides(r, hardware);
        const CaseGrid grid(specs, o, r.quick);
        const auto eager = eager_grid(specs, o, r.quick);
        EXPECT_EQ(text_of(grid.cases()), text_of(eager)) << preset.name << " " << r.experiment;
        EXPECT_EQ(grid.count(), eager.size()) << preset.name << " " << r.experiment;
        // What check_cases is given: each combination once, in the order the cases first have it.
        const std::vector<std::string> names = {"effects", "scene", "technique"};
        std::vector<ParamSet> combos;
        std::set<std::vector<std::string>> seen;
        for (const auto& c : eager) {
          std::vector<std::pair<std::string, std::string>> v;
          for (const auto& n : names)
            if (c.has(n)) v.emplace_back(n, c.get(n));
          std::vector<std::string> key;
          for (const auto& kv : v) key.push_back(kv.second);
          if (seen.insert(key).second) combos.emplace_back(std::move(v));
        }
        EXPECT_EQ(text_of(grid.distinct(names)), text_of(combos)) << preset.name << " " << r.experiment;
        ++grids;
      }
  }
  // The experiments' default and --quick grids too.
  for (const auto& e : registry.all())
    for (bool quick : {false, true})
      EXPECT_EQ(text_of(CaseGrid(registry.params_of(*e), {}, quick).cases()),
                text_of(eager_grid(registry.params_of(*e), {}, quick)))
          << e->name();
  EXPECT_GE(grids, 20u);
}

// The former plan_units: the product in memory, cut into groups, each unit to the least-loaded shard.
std::vector<std::string> eager_units(const std::vector<Planned>& plan, const RunOptions& options, ShardSpec shard) {
  std::vector<RunUnit> units;
  for (size_t i = 0; i < plan.size(); ++i) {
    const Planned& p = plan[i];
    const auto cases = p.grid->cases();
    const bool isolate = options.isolate == "always" || (options.isolate == "auto" && p.exp->hang_prone());
    if (isolate) {
      for (const auto& c : cases) units.push_back({i, true, GroupPlan{{c}, {-1}, {false}}});
      continue;
    }
    const size_t chunk = options.interleave ? static_cast<size_t>(std::max(1, p.exp->max_interleave(p.res))) : 1;
    for (auto& g : plan_groups(cases, p.baseline, chunk)) units.push_back({i, false, std::move(g)});
  }
  std::vector<size_t> sizes;
  for (const auto& u : units) sizes.push_back(u.rows());
  const auto owner = assign_shards(sizes, shard.active() ? shard.count : 1);
  std::vector<std::string> out;
  for (size_t k = 0; k < units.size(); ++k) {
    if (shard.active() && owner[k] != shard.index - 1) continue;
    std::string s = std::to_string(units[k].planned) + (units[k].isolated ? " isolated" : "");
    for (size_t i = 0; i < units[k].group.cases.size(); ++i)
      s += " | " + units[k].group.cases[i].describe() + (units[k].group.shadow[i] ? " shadow" : "") + " base " +
           std::to_string(units[k].group.baseline_of[i]);
    out.push_back(s);
  }
  return out;
}

std::vector<std::string> streamed_units(const std::vector<Planned>& plan, const RunOptions& options, ShardSpec shard) {
  std::vector<std::string> out;
  for (const auto& u : plan_units(plan, options, shard)) {
    std::string s = std::to_string(u.planned) + (u.isolated ? " isolated" : "");
    for (size_t i = 0; i < u.group.cases.size(); ++i)
      s += " | " + u.group.cases[i].describe() + (u.group.shadow[i] ? " shadow" : "") + " base " +
           std::to_string(u.group.baseline_of[i]);
    out.push_back(s);
  }
  return out;
}

// Units made one at a time are the units the whole plan made: the same groups, pairing and order, and the
// same shard for each, for every preset, with and without interleaving and isolation.
TEST(Grid, StreamedUnitsAreThePlansUnitsForEveryPreset) {
  Registry registry;
  register_all_experiments(registry);
  for (const auto& listed : list_presets(default_preset_dir())) {
    const Preset preset = load_preset(default_preset_dir(), listed.name);
    for (const char* isolate : {"auto", "always"})
      for (bool interleave : {true, false}) {
        RunOptions options;
        options.isolate = isolate;
        options.interleave = interleave;
        const auto plan = make_plan(registry, preset.runs, options, false);
        for (const ShardSpec& shard : {ShardSpec{}, ShardSpec{1, 3, ""}, ShardSpec{3, 3, ""}}) {
          EXPECT_EQ(streamed_units(plan, options, shard), eager_units(plan, options, shard))
              << preset.name << " isolate=" << isolate << " interleave=" << interleave << " shard " << shard.text();
          size_t rows = 0;
          for (const auto& u : plan_units(plan, options, shard)) rows += u.rows();
          EXPECT_EQ(UnitStream(plan, options, shard).count_rows(), rows) << preset.name;
        }
      }
  }
}

// 2,000,000 cases of the oit experiment: 100000 seeds x 20 max_frags of one exact technique.
RunRequest huge_request() {
  RunRequest r;
  r.experiment = "oit";
  r.overrides = {{"scene", {"planes"}},
                 {"view", {"fwd"}},
                 {"technique", {"BASE-IS"}},
                 {"seed", parse_set_option("seed=1..100000").second},
                 {"max_frags", parse_set_option("max_frags=1..20").second}};
  return r;
}

TEST(Grid, AHugeGridIsCountedAndRefusedWithItsCountWithoutBeingBuilt) {
  Registry registry;
  register_all_experiments(registry);
  try {
    check_requests(registry, {huge_request()});
    ADD_FAILURE() << "a 2,000,000-case grid passed the default --max-cases";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("has 2000000 cases, more than 100000"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(check_requests(registry, {huge_request()}, false, 3000000));
  try {
    check_requests(registry, {huge_request(), huge_request()}, false, 3000000);
    ADD_FAILURE() << "two 2,000,000-case grids passed --max-cases 3000000";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("the run has 4000000 cases"), std::string::npos) << e.what();
  }
  const CaseGrid grid(registry.params_of(*registry.find("oit")), huge_request().overrides, false, 3000000);
  EXPECT_EQ(grid.raw_size(), 2000000u);
  EXPECT_EQ(grid.count(), 2000000u);
  const ParamSet last = grid.case_at(grid.raw_size() - 1);
  EXPECT_EQ(last.get("seed"), "100000");
  EXPECT_EQ(last.get("max_frags"), "20");
}

// The process's resident memory now (VmRSS, KiB).
long resident_kib() {
  std::ifstream in("/proc/self/status");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
  return -1;
}

// How far the resident memory rises while `work` runs (it calls `sample` as it goes).
long rise_kib(const std::function<void(const std::function<void()>&)>& work) {
  const long before = resident_kib();
  long most = before;
  work([&] { most = std::max(most, resident_kib()); });
  most = std::max(most, resident_kib());
  return most - before;
}

constexpr long kBoundKib = 32 * 1024;  // what making the first units of any grid may add

// The first 2000 units of the 2,000,000-case grid, their cases built and dropped as a run does: the
// memory does not grow with the grid. The same measure on the product held in memory (50,000 of those
// cases, as the runner held all 2,000,000 before) exceeds the bound: the check can fail.
TEST(Grid, TheFirstUnitsOfATwoMillionCaseGridAreMadeInBoundedMemory) {
  Registry registry;
  register_all_experiments(registry);
  ASSERT_GT(resident_kib(), 0);
  RunOptions options;
  options.max_cases = 3000000;
  const auto plan = make_plan(registry, {huge_request()}, options, false);
  const long walked = rise_kib([&](const std::function<void()>& sample) {
    UnitStream stream(plan, options);
    RunUnit u;
    for (int k = 0; k < 2000 && stream.next(u); ++k)
      if (k % 100 == 0) sample();
    // 2000 groups of max_interleave cases, the last parameter (seed) fastest
    EXPECT_EQ(u.group.cases.back().get("seed"), std::to_string(2000 * plan[0].exp->max_interleave(plan[0].res)));
  });
  EXPECT_LT(walked, kBoundKib) << "KiB added while making 2000 units";
  auto small = huge_request();
  small.overrides["seed"] = parse_set_option("seed=1..2500").second;
  const auto small_plan = make_plan(registry, {small}, options, false);
  const long held = rise_kib([&](const std::function<void()>& sample) {
    const auto cases = small_plan[0].grid->cases();  // the eager path: every case in memory
    sample();
    EXPECT_EQ(cases.size(), 50000u);
  });
  EXPECT_GT(held, kBoundKib) << "KiB added by 50,000 cases held in memory";
}

}  // namespace
}  // namespace oitbench
