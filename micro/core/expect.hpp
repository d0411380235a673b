#pragma once
// The outcomes of a run, set beside an expected-status baseline (--expect FILE) the way driver CI keeps
// its lists of expected failures, and written as one for the next run (--write-expect FILE).
//
// A baseline file has one `PATTERN STATUS` per line; `#` starts a comment. PATTERN is a case key
// (core/plan.hpp: case_key, "oit/256x256/scene=planes/technique=BMA-IS/...") or a glob of one (`*`, `?`,
// `[...]`, fnmatch(3)); STATUS is invalid, unsupported, error, timeout or flaky (any outcome). The first
// line whose pattern matches a case decides what it is expected to end in; a case no line matches is
// expected ok.
#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "core/schema.hpp"

namespace oitbench {

// What one case ended in.
struct Outcome {
  std::string key, experiment;
  Status status = Status::Ok;
  std::string reason;
  double median_ms = std::numeric_limits<double>::quiet_NaN();  // the total's median; NaN: no times
};

struct Expectation {
  std::string pattern, status;  // status: "invalid", "unsupported", "error", "timeout" or "flaky"
  std::string where;            // FILE:LINE
};

// Throws UsageError naming FILE:LINE for a malformed line or an unknown status (FileError for a file that
// cannot be read).
std::vector<Expectation> load_expectations(const std::string& path);
std::vector<Expectation> parse_expectations(const std::string& text, const std::string& path);

// An outcome against the baseline: expected or not, and why.
struct Verdict {
  bool expected = true;
  std::string message;                // unexpected: "new invalid: REASON", "fixed: expected invalid (E:3), now ok; ..."
  const Expectation* line = nullptr;  // the line that matched; null: none (expected ok)
};
Verdict judge(const std::vector<Expectation>& baseline, const Outcome& outcome);

// The patterns that match none of `keys` (every case of the run's grid, every shard's): "FILE:LINE:
// 'PATTERN' matches no case of this run", for a warning.
std::vector<std::string> unmatched_patterns(const std::vector<Expectation>& baseline,
                                            const std::vector<std::string>& keys);
// The same over keys that are walked, not held: `walk` calls its argument with each key and stops when it
// returns false (once every pattern matched one).
using KeyWalk = std::function<void(const std::function<bool(const std::string&)>&)>;
std::vector<std::string> unmatched_patterns(const std::vector<Expectation>& baseline, const KeyWalk& walk);

// The baseline this run would expect: every case that did not end ok with its status (its reason as a
// comment), then the `flaky` lines of `kept` (a baseline's, which one run cannot tell) as they were.
std::string expectation_text(const std::vector<Outcome>& outcomes, const std::vector<Expectation>& kept,
                             const std::string& header);

}  // namespace oitbench
