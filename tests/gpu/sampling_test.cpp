// Samples sized by their statistics and paired speedups, end to end on the embedded default (issue 17):
// a short repetition is run several times per sample, scalable work is scaled down and the times back up,
// the stopping rule stops at its target or at a limit and says which, a fixed count is kept and flagged
// when it is too small for an interval, and every case's baseline runs in its interleaved group.
#include <cmath>
#include <set>

#include "support/test_support.hpp"

namespace oitbench::test {

namespace {

bool contains(const std::string& s, const std::string& what) { return s.find(what) != std::string::npos; }

std::vector<std::map<std::string, std::string>> run_rows(const std::string& name, std::vector<std::string> args,
                                                         std::string* raw_path = nullptr) {
  auto dir = temp_dir(name);
  auto out = (dir / "run.csv").string();
  std::vector<std::string> cmd = {"run"};
  cmd.insert(cmd.end(), args.begin(), args.end());
  cmd.insert(cmd.end(), {"--out", out, "--no-progress"});
  if (raw_path) {
    *raw_path = (dir / "raw.csv").string();
    cmd.insert(cmd.end(), {"--raw", *raw_path});
  }
  auto r = run_oitbench(cmd);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return read_csv_rows(out);
}

double num(const std::map<std::string, std::string>& row, const std::string& col) { return std::stod(row.at(col)); }

}  // namespace

TEST(Sampling, AShortRepetitionRunsSeveralTimesPerSample) {
  // One draw at 16x16 takes far less than 200 ms: a sample repeats it.
  auto rows = run_rows("short", {"occupancy", "--set", "variant=dynamic", "--set", "size=1", "--set", "draws=1",
                                 "--resolution", "16x16", "--reps", "3", "--min-sample-ms", "200"});
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0]["status"], "ok") << rows[0]["reason"];
  EXPECT_GT(num(rows[0], "sample_runs"), 1);
  EXPECT_EQ(rows[0]["sample_units"], "1");
  EXPECT_EQ(rows[0]["stop"], "fixed");
  EXPECT_EQ(rows[0]["reps"], "3");
  // The time stays per repetition (one draw), far below the 200 ms the sample lasted.
  EXPECT_LT(num(rows[0], "median_ms"), 100);
  EXPECT_TRUE(contains(rows[0]["reason"], "3 sample(s): too few for a 95% interval of the median (6 needed)"))
      << rows[0]["reason"];
  EXPECT_TRUE(rows[0]["ci_lo_ms"].empty());
}

// The warm-up ends when timings settle (runner.cpp: keep_settled_warmup): a last warm-up repetition the
// first timed one shows had settled counts as the first sample, so a fixed count still gets exactly its
// repetitions, one of them the warm-up's, and the raw file one row per sample, rounds numbered from 0.
// --warmup-settle 1000000 keeps any warm-up after the first (whose JIT it could still hold); 0 keeps none.
TEST(Sampling, ASettledWarmUpCountsAsTheFirstSample) {
  for (const char* settle : {"1000000", "0"}) {
    SCOPED_TRACE(settle);
    std::string raw;
    auto rows = run_rows(
        std::string("settle-") + settle,
        {"oit", "--set", "scene=planes", "--set", "view=fwd", "--set", "technique=BASE-IS,BASE-IMS", "--resolution",
         "32x32", "--reps", "4", "--warmup", "2", "--min-sample-ms", "0", "--warmup-settle", settle},
        &raw);
    const bool kept = std::string(settle) != "0";
    size_t totals = 0;
    for (auto& row : rows) {
      if (row["pass"] != "total") continue;
      ++totals;
      EXPECT_EQ(row["status"], "ok") << row["reason"];
      EXPECT_EQ(row["reps"], "4");
      EXPECT_EQ(row["samples"], "4");
      EXPECT_EQ(row["warmup"], kept ? "1" : "2");
      EXPECT_GT(num(row, "phase_samples_s"), 0);
      EXPECT_GT(num(row, "phase_warmup_s"), 0);
    }
    EXPECT_EQ(totals, 2u);
    std::map<std::string, std::set<std::string>> reps;  // technique -> the raw total rows' rep
    size_t raw_totals = 0;
    for (auto& row : read_csv_rows(raw))
      if (row["pass"] == "total") {
        ++raw_totals;
        reps[row["technique"]].insert(row["rep"]);
      }
    EXPECT_EQ(raw_totals, 8u);
    for (const auto& [technique, r] : reps) EXPECT_EQ(r, (std::set<std::string>{"0", "1", "2", "3"})) << technique;
  }
}

TEST(Sampling, ScalableWorkRunsFewerUnitsScaledBack) {
  // --max-sample-ms below one draw: one draw per run, times scaled to the 16 draws asked for.
  std::string raw;
  auto rows = run_rows("units",
                       {"occupancy", "--set", "variant=dynamic", "--set", "size=4", "--set", "draws=16", "--resolution",
                        "64x64", "--reps", "6", "--min-sample-ms", "0", "--max-sample-ms", "0.0001"},
                       &raw);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0]["status"], "ok") << rows[0]["reason"];  // the image of one draw is validated as of 16
  EXPECT_EQ(rows[0]["sample_units"], "1");
  EXPECT_EQ(rows[0]["sample_runs"], "1");
  EXPECT_EQ(rows[0]["draws"], "16");
  EXPECT_FALSE(rows[0]["ci_lo_ms"].empty());  // 6 samples: an interval
  EXPECT_LE(num(rows[0], "ci_lo_ms"), num(rows[0], "median_ms"));
  EXPECT_GE(num(rows[0], "ci_hi_ms"), num(rows[0], "median_ms"));
  auto raws = read_csv_rows(raw);
  ASSERT_EQ(raws.size(), 6u);
  for (auto& r : raws) {
    EXPECT_EQ(r["sample_units"], "1");
    EXPECT_EQ(r["width"], "64");
    EXPECT_EQ(r["draws"], "16");
  }
}

TEST(Sampling, TheStoppingRuleStopsAtItsTargetOrSaysWhyNot) {
  // A loose target is met by the first interval (6 samples); an impossible one runs to --max-reps and says so.
  // Loose is +-1000%: +-100% was missed once on a busy machine, where one of six sub-millisecond samples
  // took three times the median.
  auto loose = run_rows("loose", {"occupancy", "--set", "variant=dynamic", "--set", "size=1", "--set", "draws=4",
                                  "--resolution", "32x32", "--target-ci", "1000", "--max-reps", "20"});
  ASSERT_EQ(loose.size(), 1u);
  EXPECT_EQ(loose[0]["stop"], "target") << loose[0]["reason"];
  EXPECT_EQ(loose[0]["reps"], "6");
  EXPECT_EQ(loose[0]["samples"], "6");
  EXPECT_EQ(loose[0]["target_ci_pct"], "1000");
  EXPECT_LE(num(loose[0], "ci_pct"), 1000);

  auto tight = run_rows("tight", {"occupancy", "--set", "variant=dynamic", "--set", "size=1", "--set", "draws=4",
                                  "--resolution", "32x32", "--target-ci", "0.01", "--max-reps", "8"});
  ASSERT_EQ(tight.size(), 1u);
  EXPECT_EQ(tight[0]["status"], "ok");
  EXPECT_EQ(tight[0]["stop"], "max-reps");
  EXPECT_EQ(tight[0]["reps"], "8");
  EXPECT_TRUE(contains(tight[0]["reason"], "> target +-0.01% (stopped by --max-reps 8)")) << tight[0]["reason"];

  auto timed =
      run_rows("timed", {"occupancy", "--set", "variant=dynamic", "--set", "size=1", "--set", "draws=4", "--resolution",
                         "32x32", "--target-ci", "0.01", "--max-case-s", "0.05", "--max-reps", "100000"});
  ASSERT_EQ(timed.size(), 1u);
  EXPECT_EQ(timed[0]["stop"], "max-case-s") << timed[0]["samples"] << " samples of " << timed[0]["sample_runs"];
  EXPECT_LT(num(timed[0], "samples"), 100000);
  // Each sample lasts about --min-sample-ms (20): the first rounds resize it until it does. A CI machine
  // once ran 30 samples of a size chosen from a JIT-laden round within the 50 ms (about 1.7 ms each). The
  // bound is an eighth of it: under the whole suite at -j2 a correctly sized sample later read 3.7 ms, once
  // the runs it was sized from had got faster.
  if (num(timed[0], "sample_runs") < 1000) {  // runs_per_sample's cap
    EXPECT_GE(num(timed[0], "sample_runs") * num(timed[0], "median_ms"), 2.5) << timed[0]["sample_runs"];
  }
}

TEST(Sampling, EveryCaseRunsWithItsBaselineAndCarriesAPairedSpeedup) {
  std::string raw;
  auto rows = run_rows("paired",
                       {"oit", "--set", "scene=planes", "--set", "view=fwd,rev", "--set", "detail=small", "--set",
                        "technique=BASE-IS,BASE-IMS,BMA-IS", "--resolution", "32x32", "--reps", "6", "--warmup", "0",
                        "--baseline", "technique=BASE-IS"},
                       &raw);
  std::set<std::string> seen;
  for (auto& row : rows) {
    ASSERT_EQ(row["status"], "ok") << row["reason"];
    EXPECT_EQ(row["baseline"], "technique=BASE-IS");
    const std::string id = row["technique"] + " " + row["view"] + " " + row["pass"];
    EXPECT_TRUE(seen.insert(id).second) << id << " written twice";  // the baseline's copies write no rows
    if (row["technique"] == "BASE-IS" || row["pass"] == "count" || row["pass"] == "mask") {
      EXPECT_TRUE(row["speedup"].empty()) << id;  // the baseline itself, and passes it does not have
    } else {
      ASSERT_FALSE(row["speedup"].empty()) << id;
      EXPECT_GT(num(row, "speedup"), 0);
      EXPECT_LE(num(row, "speedup_ci_lo"), num(row, "speedup"));
      EXPECT_GE(num(row, "speedup_ci_hi"), num(row, "speedup"));
    }
  }
  // Per view: BASE-IS and BASE-IMS (capture, resolve, total), BMA-IS (capture, count, mask, resolve, total).
  EXPECT_EQ(seen.size(), 22u) << "rows: " << rows.size();
  // The raw file: every group holds a BASE-IS, and each other technique shares a group with one of its view.
  std::map<std::string, std::set<std::string>> group_members;
  for (auto& r : read_csv_rows(raw))
    if (r["pass"] == "total") group_members[r["group"]].insert(r["technique"] + "/" + r["view"]);
  EXPECT_EQ(group_members.size(), 2u);  // at 32x32 oit interleaves up to 8 cases: one group per view
  for (auto& [g, members] : group_members) {
    EXPECT_EQ(members.size(), 3u);
    std::string view;
    bool has_base = false;
    for (auto& m : members) {
      has_base |= m.rfind("BASE-IS/", 0) == 0;
      auto v = m.substr(m.find('/') + 1);
      EXPECT_TRUE(view.empty() || view == v) << "group " << g << " mixes views";
      view = v;
    }
    EXPECT_TRUE(has_base) << "group " << g;
  }
}

TEST(Sampling, ABaselineThatNamesNoParameterIsAUsageError) {
  auto r = run_oitbench({"run", "oit", "--quick", "--baseline", "tecnique=BASE-IS", "--out", "-"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "the baseline names no parameter 'tecnique'")) << r.err;
}

}  // namespace oitbench::test
