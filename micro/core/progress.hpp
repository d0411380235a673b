#pragma once
// The progress line of a long run on stderr: which cases, which repetition, elapsed and remaining.
#include <chrono>
#include <cstddef>
#include <string>

namespace oitbench {

class Progress {
 public:
  Progress(bool enabled, size_t total_cases) : enabled_(enabled), total_(total_cases) {}
  // `done` cases are finished; a group of `group` cases (0 between groups) is at repetition step/steps.
  void report(const std::string& experiment, size_t done, size_t group, int step, int steps) const;
  void finish() const;  // ends the line

 private:
  bool enabled_;
  size_t total_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace oitbench
