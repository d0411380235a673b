#include "core/sampling.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/stats.hpp"

namespace oitbench {

namespace {

// P(Binomial(n, 1/2) <= j), summed in logs so large n stays finite.
double binomial_half_cdf(int n, int j) {
  double total = 0;
  for (int i = 0; i <= j; ++i)
    total += std::exp(std::lgamma(n + 1.0) - std::lgamma(i + 1.0) - std::lgamma(n - i + 1.0) - n * std::log(2.0));
  return total;
}

// The largest k with P(B < k) <= alpha/2, i.e. P(B <= k-1) <= alpha/2; 0 when even k = 1 fails.
int order_index(int n, double confidence) {
  const double tail = (1.0 - confidence) / 2.0;
  int k = 0;
  while (k + 1 <= (n + 1) / 2 && binomial_half_cdf(n, k) <= tail) ++k;
  return k;
}

std::string percent(double fraction) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g%%", fraction * 100.0);
  return buf;
}

}  // namespace

Interval median_interval(std::vector<double> v, double confidence) {
  Interval ci;
  const int n = static_cast<int>(v.size());
  const int k = order_index(n, confidence);
  if (k < 1) return ci;
  std::sort(v.begin(), v.end());
  ci.lo = v[static_cast<size_t>(k - 1)];
  ci.hi = v[static_cast<size_t>(n - k)];
  ci.ok = true;
  return ci;
}

int min_samples_for_interval(double confidence) {
  int n = 1;
  while (order_index(n, confidence) < 1) ++n;
  return n;
}

double relative_half_width(const Interval& ci, double median) {
  if (!ci.ok || !(median > 0)) return std::numeric_limits<double>::infinity();
  return std::max(median - ci.lo, ci.hi - median) / median;
}

int SamplingPolicy::min_reps() const { return std::min(max_reps, min_samples_for_interval()); }

int runs_per_sample(double rep_ms, double min_sample_ms, int max_runs) {
  if (!(rep_ms > 0) || !(min_sample_ms > rep_ms)) return 1;
  return std::clamp(static_cast<int>(std::ceil(min_sample_ms / rep_ms)), 1, max_runs);
}

int units_per_run(double rep_ms, int nominal, double min_sample_ms, double max_sample_ms) {
  if (nominal <= 1 || !(rep_ms > 0) || !(max_sample_ms > 0) || rep_ms <= max_sample_ms) return std::max(nominal, 1);
  const double per_unit = rep_ms / nominal;
  // As many units as fit in max_sample_ms, but enough for min_sample_ms, and at least one.
  int units = static_cast<int>(std::floor(max_sample_ms / per_unit));
  units = std::max(units, static_cast<int>(std::ceil(min_sample_ms / per_unit)));
  return std::clamp(units, 1, nominal);
}

bool warmup_settled(double warm_ms, double first_ms, double tolerance) {
  return warm_ms > 0 && first_ms > 0 && warm_ms <= first_ms * (1.0 + tolerance);
}

StopReason stop_group(const SamplingPolicy& p, const std::vector<std::vector<double>>& samples, double spent_s) {
  size_t reps = 0;
  for (const auto& s : samples) reps = std::max(reps, s.size());
  if (!p.adaptive) return static_cast<int>(reps) >= p.reps ? StopReason::Fixed : StopReason::Continue;
  if (static_cast<int>(reps) >= p.max_reps) return StopReason::MaxReps;
  if (spent_s >= p.max_case_s * static_cast<double>(std::max<size_t>(samples.size(), 1))) return StopReason::MaxTime;
  if (static_cast<int>(reps) < p.min_reps()) return StopReason::Continue;
  for (const auto& s : samples) {
    if (s.empty()) continue;  // a case that stopped running (failed) does not hold the others
    if (relative_half_width(median_interval(s), median_of(s)) > p.target_ci) return StopReason::Continue;
  }
  return StopReason::Target;
}

StopReason step_group(const SamplingPolicy& p, const std::vector<std::vector<double>>& samples,
                      const std::vector<int>& baseline_of, double spent_s, std::vector<bool>& done) {
  const size_t n = samples.size();
  done.resize(n, false);
  if (p.adaptive)
    for (int baselines = 0; baselines < 2; ++baselines)  // the cases first, then the baselines they free
      for (size_t i = 0; i < n; ++i) {
        bool is_baseline = false, pairs_open = false;
        for (size_t j = 0; j < n && j < baseline_of.size(); ++j)
          if (baseline_of[j] == static_cast<int>(i)) {
            is_baseline = true;
            pairs_open |= !samples[j].empty() && !done[j];
          }
        if (done[i] || samples[i].empty() || is_baseline != (baselines == 1) || pairs_open) continue;
        done[i] = stop_group(p, {samples[i]}, 0) == StopReason::Target;
      }
  // The limits count every case that runs or ran (one that stopped leaves its share of the time, one that
  // failed does not); the target only those still running.
  std::vector<std::vector<double>> counted;
  bool running = false;
  for (size_t i = 0; i < n; ++i)
    if (!samples[i].empty()) {
      counted.push_back(done[i] ? std::vector<double>{} : samples[i]);
      running |= !done[i];
    }
  if (!counted.empty() && !running) return StopReason::Target;
  return stop_group(p, counted, spent_s);
}

std::string ci_note(const SamplingPolicy& p, const std::vector<double>& s, StopReason why) {
  if (s.empty()) return "";
  const Interval ci = median_interval(s);
  if (!ci.ok)
    return std::to_string(s.size()) + " sample(s): too few for a 95% interval of the median (" +
           std::to_string(min_samples_for_interval()) + " needed)";
  if (!p.adaptive) return "";
  const double rel = relative_half_width(ci, median_of(s));
  if (rel <= p.target_ci) return "";
  char seconds[32];
  std::snprintf(seconds, sizeof seconds, "%g", p.max_case_s);
  const std::string by =
      why == StopReason::MaxTime ? std::string("--max-case-s ") + seconds : "--max-reps " + std::to_string(p.max_reps);
  return "ci +-" + percent(rel) + " > target +-" + percent(p.target_ci) + " (stopped by " + by + ")";
}

const char* stop_reason_name(StopReason r) {
  switch (r) {
    case StopReason::Continue:
      return "continue";
    case StopReason::Fixed:
      return "fixed";
    case StopReason::Target:
      return "target";
    case StopReason::MaxReps:
      return "max-reps";
    case StopReason::MaxTime:
      return "max-case-s";
  }
  return "?";
}

}  // namespace oitbench
