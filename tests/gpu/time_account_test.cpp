// The time account end to end (core/phases.hpp, docs/measurement.md "Where a run's time goes"): every
// case's total row has its wall time and phases, present, not negative and adding up to case_wall_s;
// the cases' walls fit in the process's; the run's closing line gives the shares.
#include <chrono>
#include <filesystem>
#include <functional>
#include <map>

#include "core/phases.hpp"
#include "support/test_support.hpp"

namespace oitbench::test {

namespace {

double column(const Row& row, const std::string& name) {
  auto it = row.find(name);
  if (it == row.end() || it->second.empty()) {
    ADD_FAILURE() << "column " << name << " missing or empty";
    return -1;
  }
  return std::stod(it->second);
}

// Checks every total row's account; returns the sum of their case_wall_s.
double check_accounts(const std::vector<Row>& rows) {
  double walls = 0;
  size_t totals = 0;
  for (const auto& row : rows) {
    if (row.at("pass") != "total") {
      EXPECT_TRUE(row.at("case_wall_s").empty()) << "the account is on the total row only";
      continue;
    }
    ++totals;
    const double wall = column(row, "case_wall_s");
    double sum = 0;
    for (Phase p : kAllPhases) {
      const double s = column(row, phase_column(p));
      EXPECT_GE(s, 0) << phase_column(p);
      sum += s;
    }
    EXPECT_GT(wall, 0);
    EXPECT_NEAR(sum, wall, 0.05 * wall) << row.at("technique");
    walls += wall;
  }
  EXPECT_GT(totals, 0u);
  return walls;
}

}  // namespace

TEST(TimeAccount, PhasesAddUpToEachCaseAndTheCasesFitInTheRun) {
  auto out = temp_dir("account") / "a.csv";
  const auto t0 = std::chrono::steady_clock::now();
  auto r = run_oitbench({"run", "oit", "--set", "scene=planes", "--set", "technique=BASE-IS,MLAB", "--resolution",
                         "64x64", "--reps", "3", "--out", out.string(), "--no-progress"});
  const double process_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto rows = read_csv_rows(out);
  ASSERT_FALSE(rows.empty());
  const double walls = check_accounts(rows);
  EXPECT_LE(walls, process_s);
  for (const auto& row : rows) {
    if (row.at("pass") != "total") continue;
    EXPECT_EQ(row.at("status"), "ok") << row.at("reason");
    // The runner's phases and the cases' own stretches are all charged (the warm-up where it stayed one:
    // a warm-up that settled counts as a sample, and its row says warmup=0).
    for (const char* c :
         {"phase_scene_s", "phase_samples_s", "phase_readback_s", "phase_reference_s", "phase_validate_s"})
      EXPECT_GT(column(row, c), 0) << c << " of " << row.at("technique");
    if (row.at("warmup") != "0") {
      EXPECT_GT(column(row, "phase_warmup_s"), 0) << row.at("technique");
    }
    if (row.at("technique") == "BASE-IS") {
      EXPECT_GT(column(row, "phase_pool_s"), 0);
    }
  }
  EXPECT_NE(r.err.find("oitbench: time "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("timed samples "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("reference+validation "), std::string::npos) << r.err;
}

// A baseline paired with more candidates than one group holds runs again in the next group (a shadow,
// core/groups.cpp) and writes no row: its time is shared among that group's rows, phase by phase, so the
// rows' timed samples are the run's (the closing line's, printed to 0.1 s), not less by the shadow's.
TEST(TimeAccount, ABaselineRunAgainForMoreCandidatesIsInTheRows) {
  // 8 candidates beside their baseline at 64x64: the oit experiment interleaves at most 8 cases there, so
  // the baseline runs again, as a shadow, beside the eighth.
  auto out = temp_dir("account-shadow") / "a.csv";
  auto r = run_oitbench({"run", "oit", "--set", "scene=planes", "--set", "view=fwd", "--set",
                         "technique=BASE-IS,BASE-IMS,BASE-RBS-L,BMA-IS,BMA-IMS,BMA-RBS-L,CS-IS,CS-IMS,CS-RBS-L",
                         "--baseline", "technique=BASE-IS", "--resolution", "64x64", "--reps", "10", "--warmup-settle",
                         "0", "--out", out.string(), "--no-progress"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto rows = read_csv_rows(out);
  check_accounts(rows);
  double samples = 0;
  size_t totals = 0;
  for (const auto& row : rows)
    if (row.at("pass") == "total") {
      samples += column(row, "phase_samples_s");
      ++totals;
    }
  EXPECT_EQ(totals, 9u) << "the shadow writes no row";
  const auto at = r.err.find("timed samples ");
  ASSERT_NE(at, std::string::npos) << r.err;
  const double line = std::stod(r.err.substr(at + std::string("timed samples ").size()));
  EXPECT_NEAR(samples, line, 0.06 + 0.02 * line) << r.err;
}

TEST(TimeAccount, AnIsolatedCaseBringsItsAccount) {
  auto out = temp_dir("account-isolated") / "a.csv";
  auto r = run_oitbench({"run", "occupancy", "--quick", "--set", "variant=unrolled", "--set", "size=4", "--isolate",
                         "always", "--out", out.string(), "--no-progress"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  check_accounts(read_csv_rows(out));
  EXPECT_NE(r.err.find("oitbench: time "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("isolated cases' start "), std::string::npos) << r.err;
}

}  // namespace oitbench::test

namespace oitbench::test {

// The exact techniques' cases of a run that capture the same fragments share one pool sizing
// (exact_case.cpp: size_pool); every check still sees each case's own capture: a case that loses
// fragments (fault=lose-fragment, in the sizing's key) is still invalid beside valid ones of the same view.
TEST(TimeAccount, ASharedPoolSizingKeepsEveryCheck) {
  auto out = temp_dir("account-shared") / "a.csv";
  auto r = run_oitbench({"run", "oit", "--set", "scene=planes", "--set", "view=fwd,rev", "--set",
                         "technique=BASE-IS,CPU-NATIVE", "--set", "fault=none,lose-fragment", "--resolution", "64x64",
                         "--reps", "1", "--warmup", "0", "--out", out.string(), "--no-progress"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::map<std::string, std::string> fragments;  // view -> total_fragments of its fault-free cases
  size_t totals = 0;
  for (const auto& row : read_csv_rows(out)) {
    if (row.at("pass") != "total") continue;
    ++totals;
    const std::string what = row.at("view") + " " + row.at("technique") + " " + row.at("fault");
    if (row.at("fault") == "lose-fragment") {
      EXPECT_EQ(row.at("status"), "invalid") << what;
      EXPECT_NE(row.at("reason").find("fragments lost"), std::string::npos) << what << ": " << row.at("reason");
      continue;
    }
    EXPECT_EQ(row.at("status"), "ok") << what << ": " << row.at("reason");
    auto [it, first] = fragments.emplace(row.at("view"), row.at("total_fragments"));
    if (!first) {
      EXPECT_EQ(it->second, row.at("total_fragments")) << what;
    }
  }
  EXPECT_EQ(totals, 8u);
}

// One oit run of planes rev at 64x64 (one repetition, no warm-up) with `sets` added, into `out`; its rows.
static std::vector<Row> run_planes_rev_64(const std::filesystem::path& out, const std::vector<std::string>& sets) {
  std::vector<std::string> args = {"run", "oit", "--out", out.string()};
  args.insert(args.end(), sets.begin(), sets.end());
  for (const char* a : {"--set", "scene=planes", "--set", "view=rev", "--resolution", "64x64", "--reps", "1",
                        "--warmup", "0", "--no-progress"})
    args.emplace_back(a);
  auto r = run_oitbench(args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return read_csv_rows(out);
}

// The total rows of a run where wrong-result cases share a reference with valid ones: each wrong one is
// invalid, each other one ok and seen by `each_ok` (with its technique and fault); returns how many rows.
static size_t check_wrong_results_stay_invalid(const std::vector<Row>& rows,
                                               const std::function<void(const Row&, const std::string&)>& each_ok) {
  size_t totals = 0;
  for (const auto& row : rows) {
    if (row.at("pass") != "total") continue;
    ++totals;
    const std::string what = row.at("technique") + " " + row.at("fault");
    if (row.at("fault") == "wrong-result") {
      EXPECT_EQ(row.at("status"), "invalid") << what;
      continue;
    }
    EXPECT_EQ(row.at("status"), "ok") << what << ": " << row.at("reason");
    each_ok(row, what);
  }
  return totals;
}

// The approximate techniques' cases of a run that see the same fragments share one reference view
// (approx_case.cpp: reference_view); each still compares its own image: a wrong result (in the key) is
// still invalid beside valid cases of the same view, and a case's error is what it is in a run of its own.
TEST(TimeAccount, ASharedReferenceKeepsEveryCheck) {
  const auto dir = temp_dir("account-reference");
  auto run = [&](const std::string& name, const std::vector<std::string>& sets) {
    return run_planes_rev_64(dir / name, sets);
  };
  const auto rows = run("both.csv", {"--set", "technique=WBOIT,MLAB", "--set", "fault=none,wrong-result"});
  const auto alone = run("alone.csv", {"--set", "technique=MLAB"});
  ASSERT_FALSE(alone.empty());
  const size_t totals = check_wrong_results_stay_invalid(rows, [&](const Row& row, const std::string&) {
    if (row.at("technique") == "MLAB") {
      EXPECT_EQ(row.at("rmse"), alone.back().at("rmse"));
      EXPECT_EQ(row.at("total_fragments"), alone.back().at("total_fragments"));
    }
  });
  EXPECT_EQ(totals, 4u);
}

// Every CPU-model-checked case (the approximate techniques, MBOIT, WOIT, STOCHASTIC, SLAB) of a run that
// sees the same fragments shares one reference view (visible_capture.hpp: reference_view): a wrong result (in the key)
// is still invalid beside valid cases of the same view, and each case's error is what it is in a run of its own.
TEST(TimeAccount, EveryModelCheckedCaseSharesTheReferenceAndKeepsEveryCheck) {
  const auto dir = temp_dir("account-model-reference");
  auto run = [&](const std::string& name, const std::vector<std::string>& sets) {
    return run_planes_rev_64(dir / name, sets);
  };
  const std::vector<std::string> shared = {"MLAB", "MBOIT", "WOIT", "STOCHASTIC", "SLAB"};
  const auto rows =
      run("shared.csv", {"--set", "technique=MLAB,MBOIT,WOIT,STOCHASTIC,SLAB", "--set", "fault=none,wrong-result"});
  std::map<std::string, Row> alone;
  for (const std::string& t : {std::string("MBOIT"), std::string("STOCHASTIC")}) {
    const auto own = run(t + ".csv", {"--set", "technique=" + t});
    ASSERT_FALSE(own.empty()) << t;
    alone[t] = own.back();
  }
  const size_t totals = check_wrong_results_stay_invalid(rows, [&](const Row& row, const std::string& what) {
    if (row.at("technique") == "MLAB") {  // the approximate cases report against the scene's planes too
      EXPECT_FALSE(row.at("truth_rmse").empty()) << what << ": the geometric reference (planes are analytic)";
    }
    auto it = alone.find(row.at("technique"));
    if (it == alone.end()) return;
    for (const char* col : {"rmse", "model_rmse", "total_fragments"})
      EXPECT_EQ(row.at(col), it->second.at(col)) << what << " " << col;
  });
  EXPECT_EQ(totals, 2 * shared.size());
}

}  // namespace oitbench::test
