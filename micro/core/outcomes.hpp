#pragma once
// What a run's outcomes become at its end, for fleets and CI: the verdict against the expected-status
// baseline (--expect, core/expect.hpp), the JUnit report (--junit, core/junit.hpp) and the baseline this
// run would expect (--write-expect; with --expect and an --out file, beside it as OUT.expect).
#include <string>
#include <vector>

#include "core/expect.hpp"
#include "core/rows.hpp"
#include "core/runner.hpp"

namespace oitbench {

// Exit code 4: with --expect, an outcome the baseline did not expect.
inline constexpr int kExitUnexpected = 4;

// Where --write-expect goes: its own value, else OUT.expect beside an --out file when --expect is given.
std::string write_expect_path(const RunOptions& options);

// Writes the reports and prints the verdict; returns the exit code: `code` (the run's) without --expect,
// else 130 if interrupted, kExitUnexpected when an outcome was unexpected, 0 when all were expected.
// `unmatched`: unmatched_patterns' warnings. `run`: the run's columns (driver, gl_renderer, git_sha, ...) for the JUnit
// properties.
int report_outcomes(const RunOptions& options, const std::vector<Expectation>& baseline,
                    const std::vector<Outcome>& outcomes, const std::vector<std::string>& unmatched, const Row& run,
                    int code);

}  // namespace oitbench
