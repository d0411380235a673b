#pragma once
// How many repetitions a case gets, and how much work one sample holds (nanobench's idea: size the sample
// from what the warm-up measured, repeat until the statistics are good enough). Pure functions of the
// samples and the time spent, so a test drives them with made-up numbers.
#include <string>
#include <vector>

namespace oitbench {

// A distribution-free interval for the median: the order statistics x(k) and x(n+1-k) with k the largest
// index whose binomial tail P(Binomial(n, 1/2) < k) stays within (1 - confidence)/2. It exists only from
// min_samples_for_interval() samples on (6 at 95 %); `ok` is false below that.
struct Interval {
  double lo = 0, hi = 0;
  bool ok = false;
};
Interval median_interval(std::vector<double> samples, double confidence = 0.95);
int min_samples_for_interval(double confidence = 0.95);
// The interval's larger distance from the median, relative to the median (0.03: within +-3 %).
double relative_half_width(const Interval& ci, double median);

// How much slower than the first timed repetition a warm-up repetition may be and still count as a sample
// (warmup_settled below; --warmup-settle).
inline constexpr double kSettledTolerance = 0.10;

struct SamplingPolicy {
  bool adaptive = false;       // false: exactly `reps` repetitions (--reps N)
  int reps = 5;                // the fixed count
  double target_ci = 0.03;     // --target-ci: stop when the median's interval is within +-this
  int max_reps = 30;           // --max-reps
  double max_case_s = 30;      // --max-case-s: timed seconds per case (a group of n cases gets n times this)
  double min_sample_ms = 20;   // --min-sample-ms: a sample runs the case's repetition this long at least
  double max_sample_ms = 500;  // --max-sample-ms: above this a case with scalable work runs less of it (0: never)
  double warmup_settle = kSettledTolerance;  // --warmup-settle: keep a settled warm-up as a sample (0: never)
  int min_reps() const;                      // adaptive: min_samples_for_interval(), at most max_reps
};

// Runs of the case's repetition in one sample, so that it lasts at least min_sample_ms (1 when one run
// already does, or when nothing was measured).
int runs_per_sample(double rep_ms, double min_sample_ms, int max_runs = 1000);
// Units of work (draws) in one run of a case whose repetition is `nominal` units: fewer where a whole
// repetition would take longer than max_sample_ms, never under one unit nor below what min_sample_ms needs.
int units_per_run(double rep_ms, int nominal, double min_sample_ms, double max_sample_ms);

// Whether a warm-up repetition had already settled, so that it can count as the first sample instead of
// being thrown away (the warm-up ends when timings settle, not after a fixed count): the first timed
// repetition, run at the same size, is not faster than it by more than `tolerance` (0.10: the warm-up
// took at most 10 % longer). A repetition that held the JIT or another first-time cost never passes.
// `warm_ms`, `first_ms`: their totals on the clock the statistics use.
bool warmup_settled(double warm_ms, double first_ms, double tolerance = kSettledTolerance);

// Whether an interleaved group of cases has enough repetitions. `samples[i]` is case i's per-repetition
// times (of the statistic the stopping rule watches: the total); `spent_s` the timed seconds so far.
enum class StopReason { Continue, Fixed, Target, MaxReps, MaxTime };
StopReason stop_group(const SamplingPolicy& policy, const std::vector<std::vector<double>>& samples, double spent_s);
// One round's decision for an interleaved group under the stopping rule, case by case: a case whose own
// interval reached the target is marked done (it stops running; its rows say stop=target), except a
// baseline while a case that pairs with it still runs (baseline_of[i]: index of case i's baseline, -1 none),
// so every pair keeps its rounds. `samples[i]` empty: a case that does not run (failed). The limits
// (--max-reps, --max-case-s x the cases that ran, stopped or not) stop the rest; the group stops with
// Target once every case is done. A fixed count marks nothing and stops at the count.
StopReason step_group(const SamplingPolicy& policy, const std::vector<std::vector<double>>& samples,
                      const std::vector<int>& baseline_of, double spent_s, std::vector<bool>& done);
// For a case whose repetitions stopped: its note when its interval missed the target (empty when it made
// it, or when the count was fixed), e.g. "ci +-7.1% > target +-3% (stopped by --max-reps 30)".
std::string ci_note(const SamplingPolicy& policy, const std::vector<double>& samples, StopReason why);
const char* stop_reason_name(StopReason r);

}  // namespace oitbench
