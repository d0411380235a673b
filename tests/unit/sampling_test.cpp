#include "core/sampling.hpp"

#include <gtest/gtest.h>

#include <random>

#include "core/rows.hpp"
#include "core/stats.hpp"

namespace oitbench {

TEST(Sampling, MedianIntervalNeedsSixSamplesAt95Percent) {
  EXPECT_EQ(min_samples_for_interval(0.95), 6);
  EXPECT_FALSE(median_interval({1, 2, 3, 4, 5}).ok);
  auto ci = median_interval({6, 1, 5, 2, 4, 3});  // k = 1: the extremes (coverage 1 - 2/64)
  ASSERT_TRUE(ci.ok);
  EXPECT_DOUBLE_EQ(ci.lo, 1);
  EXPECT_DOUBLE_EQ(ci.hi, 6);
}

TEST(Sampling, MedianIntervalUsesBinomialOrderStatistics) {
  std::vector<double> v;
  for (int i = 1; i <= 9; ++i) v.push_back(i);
  auto ci = median_interval(v);  // n = 9: P(B <= 1) = 10/512 <= 0.025, P(B <= 2) = 46/512 > 0.025: k = 2
  ASSERT_TRUE(ci.ok);
  EXPECT_DOUBLE_EQ(ci.lo, 2);
  EXPECT_DOUBLE_EQ(ci.hi, 8);
  v.clear();
  for (int i = 1; i <= 100; ++i) v.push_back(i);
  ci = median_interval(v);  // n = 100: the textbook ranks 40 and 61
  EXPECT_DOUBLE_EQ(ci.lo, 40);
  EXPECT_DOUBLE_EQ(ci.hi, 61);
  EXPECT_NEAR(relative_half_width(ci, 50.5), 10.5 / 50.5, 1e-12);
}

TEST(Sampling, AWarmUpHasSettledWhenTheFirstSampleIsNotMuchFaster) {
  EXPECT_TRUE(warmup_settled(100, 100));
  EXPECT_TRUE(warmup_settled(90, 100));     // faster than the sample: nothing left to warm
  EXPECT_TRUE(warmup_settled(110, 100));    // within 10 %
  EXPECT_FALSE(warmup_settled(111, 100));   // 11 % slower: the sample says the warm-up was still warming
  EXPECT_FALSE(warmup_settled(5000, 100));  // the JIT of the first draw
  EXPECT_TRUE(warmup_settled(120, 100, 0.25));
  EXPECT_FALSE(warmup_settled(0, 100));  // nothing measured
  EXPECT_FALSE(warmup_settled(100, 0));
  EXPECT_FALSE(warmup_settled(-1, 100));  // no GPU query result
}

TEST(Sampling, SampleSizeFromTheWarmUp) {
  EXPECT_EQ(runs_per_sample(2.0, 20.0), 10);          // 2 ms repetitions: 10 per 20 ms sample
  EXPECT_EQ(runs_per_sample(3.0, 20.0), 7);           // rounded up: the sample lasts at least 20 ms
  EXPECT_EQ(runs_per_sample(50.0, 20.0), 1);          // already long enough
  EXPECT_EQ(runs_per_sample(0.0, 20.0), 1);           // nothing measured
  EXPECT_EQ(runs_per_sample(0.001, 20.0, 100), 100);  // capped
  // 64 draws of 434 ms: one draw per run; 64 draws of 1 ms stay 64.
  EXPECT_EQ(units_per_run(64 * 434.0, 64, 20, 500), 1);
  EXPECT_EQ(units_per_run(64 * 1.0, 64, 20, 500), 64);
  EXPECT_EQ(units_per_run(64 * 50.0, 64, 20, 500), 10);  // 10 draws of 50 ms fill 500 ms
  EXPECT_EQ(units_per_run(64 * 434.0, 64, 20, 0), 64);   // 0: never scaled down
  EXPECT_EQ(units_per_run(1000.0, 1, 20, 500), 1);       // nothing to scale
}

// A deterministic workload: a case whose samples scatter by `noise` (relative, uniform) around `ms`.
std::vector<std::vector<double>> drive(const SamplingPolicy& p, std::vector<double> noise, StopReason& why,
                                       double ms_per_rep = 10) {
  std::mt19937 rng(7);
  std::vector<std::vector<double>> s(noise.size());
  double spent = 0;  // a fake clock: each repetition of each case takes ms_per_rep
  while ((why = stop_group(p, s, spent)) == StopReason::Continue) {
    for (size_t i = 0; i < s.size(); ++i) {
      std::uniform_real_distribution<double> u(-noise[i], noise[i]);
      s[i].push_back(ms_per_rep * (1 + u(rng)));
      spent += ms_per_rep / 1000.0;
    }
    if (s[0].size() > 10000) break;  // a rule that never stops fails below
  }
  return s;
}

TEST(Sampling, TheStoppingRuleStopsAtTheTargetForQuietCases) {
  SamplingPolicy p;
  p.adaptive = true;
  StopReason why;
  auto s = drive(p, {0.01, 0.02}, why);
  EXPECT_EQ(why, StopReason::Target);
  EXPECT_EQ(static_cast<int>(s[0].size()), p.min_reps());  // +-2 % is inside +-3 % from the first interval on
  for (const auto& x : s) EXPECT_LE(relative_half_width(median_interval(x), median_of(x)), p.target_ci);
  EXPECT_EQ(ci_note(p, s[0], why), "");
}

TEST(Sampling, ANoisyCaseHoldsItsGroupUntilItsIntervalIsNarrow) {
  SamplingPolicy p;
  p.adaptive = true;
  p.max_reps = 1000;
  p.max_case_s = 1e9;
  StopReason why;
  auto s = drive(p, {0.01, 0.15}, why);  // +-15 %: needs many more than 6 repetitions
  EXPECT_EQ(why, StopReason::Target);
  EXPECT_GT(s[1].size(), 20u);
  EXPECT_EQ(s[0].size(), s[1].size());  // interleaved: every case of the group ran every round
  EXPECT_LE(relative_half_width(median_interval(s[1]), median_of(s[1])), p.target_ci);
}

// The same workload under step_group: a case stops at its own target, a baseline when its cases have.
std::vector<std::vector<double>> drive_cases(const SamplingPolicy& p, std::vector<double> noise,
                                             std::vector<int> baseline_of, StopReason& why, std::vector<bool>& done,
                                             double ms_per_rep = 10) {
  std::mt19937 rng(7);
  std::vector<std::vector<double>> s(noise.size());
  double spent = 0;
  done.clear();
  while ((why = step_group(p, s, baseline_of, spent, done)) == StopReason::Continue) {
    for (size_t i = 0; i < s.size(); ++i) {
      if (done[i]) continue;
      std::uniform_real_distribution<double> u(-noise[i], noise[i]);
      s[i].push_back(ms_per_rep * (1 + u(rng)));
      spent += ms_per_rep / 1000.0;
    }
    if (s.back().size() > 10000) break;
  }
  return s;
}

// The stopping rule with limits too far away to matter: only the target stops it.
SamplingPolicy target_only() {
  SamplingPolicy p;
  p.adaptive = true;
  p.max_reps = 1000;
  p.max_case_s = 1e9;
  return p;
}

TEST(Sampling, AQuietCaseStopsAtItsTargetWhileANoisyOneGoesOn) {
  const SamplingPolicy p = target_only();
  StopReason why;
  std::vector<bool> done;
  auto s = drive_cases(p, {0.01, 0.15}, {-1, -1}, why, done);
  EXPECT_EQ(why, StopReason::Target);
  EXPECT_EQ(static_cast<int>(s[0].size()), p.min_reps());  // done after the first interval
  EXPECT_GT(s[1].size(), 20u);                             // the noisy one alone went on
  EXPECT_TRUE(done[0] && done[1]);
  for (const auto& x : s) EXPECT_LE(relative_half_width(median_interval(x), median_of(x)), p.target_ci);
}

TEST(Sampling, ABaselineRunsAsLongAsACaseItPairsWith) {
  const SamplingPolicy p = target_only();
  StopReason why;
  std::vector<bool> done;
  // Case 0 is the baseline of 1 (noisy) and 2 (quiet); 3 is on its own.
  auto s = drive_cases(p, {0.01, 0.15, 0.01, 0.01}, {-1, 0, 0, -1}, why, done);
  EXPECT_EQ(why, StopReason::Target);
  EXPECT_GT(s[1].size(), 20u);
  EXPECT_EQ(s[0].size(), s[1].size());  // every sample of the noisy case has its baseline's of the same round
  EXPECT_EQ(static_cast<int>(s[2].size()), p.min_reps());
  EXPECT_EQ(static_cast<int>(s[3].size()), p.min_reps());
  // A baseline whose cases failed (no samples) is free to stop at its own target.
  std::vector<std::vector<double>> failed = {std::vector<double>(6, 10.0), {}};
  done.clear();
  EXPECT_EQ(step_group(p, failed, {-1, 0}, 0, done), StopReason::Target);
  EXPECT_TRUE(done[0]);
}

TEST(Sampling, TheGroupsLimitsCountTheCasesThatStopped) {
  SamplingPolicy p;
  p.adaptive = true;
  p.max_reps = 1000;
  p.max_case_s = 0.75;  // two cases: 1.5 s in all, however many still run
  StopReason why;
  std::vector<bool> done;
  auto s = drive_cases(p, {0.0, 0.5}, {-1, -1}, why, done, 100);
  EXPECT_EQ(why, StopReason::MaxTime);
  EXPECT_TRUE(done[0]);
  EXPECT_FALSE(done[1]);
  EXPECT_EQ(s[0].size(), 6u);
  EXPECT_EQ(s[1].size(), 6u + 3u);  // 1.2 s for both, then 0.3 s for the noisy one alone
  // A case that failed (no samples) leaves no share: one running case past its 0.75 s is stopped.
  std::vector<std::vector<double>> with_failed = {{10, 15, 8, 12, 20, 9}, {}};
  done.clear();
  EXPECT_EQ(step_group(p, with_failed, {-1, -1}, 0.8, done), StopReason::MaxTime);
  // A fixed count stops nobody early.
  SamplingPolicy fixed;
  fixed.reps = 4;
  s = drive_cases(fixed, {0.0, 0.5}, {-1, -1}, why, done);
  EXPECT_EQ(why, StopReason::Fixed);
  EXPECT_EQ(s[0].size(), 4u);
  EXPECT_EQ(s[1].size(), 4u);
  EXPECT_FALSE(done[0] || done[1]);
}

TEST(Sampling, LimitsStopWhatTheTargetCannot) {
  SamplingPolicy p;
  p.adaptive = true;
  p.max_reps = 12;
  StopReason why;
  auto s = drive(p, {0.5}, why);
  EXPECT_EQ(why, StopReason::MaxReps);
  EXPECT_EQ(s[0].size(), 12u);
  EXPECT_NE(ci_note(p, s[0], why).find("stopped by --max-reps 12"), std::string::npos) << ci_note(p, s[0], why);

  p.max_reps = 1000;
  p.max_case_s = 0.45;  // two cases of 100 ms each: 0.9 s in all, reached in round 5
  s = drive(p, {0.5, 0.5}, why, 100);
  EXPECT_EQ(why, StopReason::MaxTime);
  EXPECT_EQ(s[0].size(), 5u);
  EXPECT_NE(ci_note(p, s[0], why).find("too few"), std::string::npos) << ci_note(p, s[0], why);
}

TEST(Sampling, AFixedCountIsKeptAndFlaggedWhenItGivesNoInterval) {
  SamplingPolicy p;
  p.reps = 2;
  StopReason why;
  auto s = drive(p, {0.0}, why);
  EXPECT_EQ(why, StopReason::Fixed);
  EXPECT_EQ(s[0].size(), 2u);
  EXPECT_EQ(ci_note(p, s[0], why), "2 sample(s): too few for a 95% interval of the median (6 needed)");
  p.reps = 7;
  s = drive(p, {0.5}, why);
  EXPECT_EQ(s[0].size(), 7u);
  EXPECT_EQ(ci_note(p, s[0], why), "");  // a fixed count is not held to the target
}

}  // namespace oitbench

namespace oitbench {

// The stopping rule watches the total; a pass row whose own interval missed the target says so in its
// reason (every timed row within the target or flagged), unless the count was fixed.
TEST(Sampling, APassWhoseIntervalMissedTheTargetSaysSo) {
  RowSettings s;
  s.experiment = "oit";
  s.target_ci = 0.05;
  CaseRecord c;
  c.pass_names = {"capture", "resolve"};
  c.stop = "target";
  c.cpu["total"] = {100, 101, 99, 100, 100.5, 99.5, 100, 100.2};
  c.cpu["capture"] = c.cpu["total"];
  c.cpu["resolve"] = {50, 60, 40, 55, 45, 70, 30, 52};
  for (const auto& [pass, v] : c.cpu) c.gpu[pass] = std::vector<double>(v.size(), -1);
  auto reason_of = [&](const std::string& pass) {
    for (auto& row : summary_rows(s, c))
      if (row.at("pass") == pass) return row.at("reason");
    return std::string("(no row)");
  };
  EXPECT_NE(reason_of("resolve").find("this pass: ci +-"), std::string::npos) << reason_of("resolve");
  EXPECT_NE(reason_of("resolve").find("> target +-5%"), std::string::npos) << reason_of("resolve");
  EXPECT_EQ(reason_of("capture"), "");
  EXPECT_EQ(reason_of("total"), "");
  c.stop = "fixed";  // --reps N: the count was the user's, and the total says nothing either
  EXPECT_EQ(reason_of("resolve"), "");
}

}  // namespace oitbench
