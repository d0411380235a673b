#pragma once
// A case's results as CSV rows: the statistics of each pass under the primary clock beside both
// clocks' medians, the status and reason, the metrics, and the parameters the case uses.
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/phases.hpp"
#include "core/registry.hpp"
#include "core/sampling.hpp"
#include "core/schema.hpp"
#include "core/timer.hpp"

namespace oitbench {

using Row = std::map<std::string, std::string>;

std::string fmt_number(double v, int prec = 4);  // empty for NaN and infinities

// What one case produced, kept until its rows are written.
struct CaseRecord {
  ParamSet params;
  std::string key;  // case_key (core/plan.hpp) of the grid's case, before prepare resolves any value
  std::string variant;
  Status status = Status::Ok;
  std::string reason;
  double compile_ms = std::numeric_limits<double>::quiet_NaN(), warmup_ms = std::numeric_limits<double>::quiet_NaN();
  std::string program_cache;  // hit | miss | partial | off: whether compile_ms paid the compile
  std::vector<std::string> pass_names;
  std::map<std::string, std::vector<double>> cpu, gpu;  // by pass, "total" included; gpu < 0: no result
  std::map<std::string, std::string> metrics;           // the instance's and the validation's
  std::string note;                                     // the validation's note on an ok case
  int sample_runs = 1;                                  // runs of the repetition per sample
  int sample_units = 0;                         // units of work per run (0: the experiment does not scale its work)
  std::string stop;                             // why the repetitions stopped (stop_reason_name)
  std::string baseline;                         // NAME=VALUE;... of the case the speedup divides by (empty: none)
  const CaseRecord* baseline_record = nullptr;  // that case's record, run in the same group (null: no speedup)
  PhaseTimes phases;                            // where its wall time went (core/phases.hpp)
  bool accounted = false;                       // the runner kept that account (case_wall_s and phase_*_s)
  int warmup_kept = 0;                          // warm-up repetitions that had settled, kept as samples
  std::vector<double> mem_ns;                   // the host's memory latency after each of its timed rounds

  void fail(Status s, const std::string& why);  // the first failure is the one kept
  // Appends to what the rows' reason will say: the note of an ok case, the reason of another.
  void add_note(const std::string& text);
  // Records one timed repetition; returns the sum of its GPU pass times (< 0 when one is missing).
  double add_repetition(const std::vector<PassSample>& samples, double total_ms);
};

struct RowSettings {
  Row run;  // the run's columns (backend, renderer, git_sha, ...)
  std::string experiment;
  Resolution res;
  int reps = 0, warmup = 0;
  double target_ci = 0;      // the stopping rule's target (fraction); 0: a fixed count
  int group = 0;             // the interleaved group's index in the run (raw rows)
  bool gpu_primary = false;  // GL queries are the primary clock where every repetition has one
  bool synchronised = true;  // passes bracketed by glFinish: their CPU time is their work
};

// One row per pass (when there are several) and `total`.
std::vector<Row> summary_rows(const RowSettings& s, const CaseRecord& c);
// The --raw rows of one repetition: one per pass (when there are several) and `total`.
std::vector<Row> raw_rows(const RowSettings& s, const CaseRecord& c, int rep, const std::vector<PassSample>& samples,
                          double total_ms, double gpu_total_ms);

// Paired speedup of `c` over `base` for one pass: median and 95% interval of base[i] / c[i] over the
// repetitions both have (they ran in the same rounds of one interleaved group), on the primary clock.
struct Speedup {
  double median = 0;
  Interval ci;
  size_t pairs = 0;
};
std::optional<Speedup> paired_speedup(const CaseRecord& base, const CaseRecord& c, const std::string& pass,
                                      bool gpu_primary);

// Where queries are the primary clock, a CPU clock this many times off them means one is wrong.
inline constexpr double kTimerDisagreement = 2.0;

}  // namespace oitbench
