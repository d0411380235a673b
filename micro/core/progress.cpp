#include "core/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace oitbench {

void Progress::report(const std::string& experiment, size_t done_cases, size_t group, int step, int steps) const {
  if (!enabled_) return;
  double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  // The group's cases are not counted as done until it ends, its last repetition included.
  double done = static_cast<double>(done_cases) +
                (group ? static_cast<double>(group) * std::min(step, steps) / std::max(steps, 1) : 0.0);
  double frac = done / static_cast<double>(std::max<size_t>(total_, 1));
  char eta[32] = "?";
  if (frac > 0.005) std::snprintf(eta, sizeof eta, "%.0f s", elapsed / frac - elapsed);
  char cases[64];
  if (group > 1)
    std::snprintf(cases, sizeof cases, "cases %zu-%zu of %zu", done_cases + 1, done_cases + group, total_);
  else
    std::snprintf(cases, sizeof cases, "case %zu of %zu", std::min(done_cases + (group ? 1 : 0), total_),
                  total_);  // between groups: the last finished one
  std::fprintf(stderr, "\r[%s] %s  rep %d/%d  elapsed %.1f s  remaining ~%s   ", cases, experiment.c_str(), step, steps,
               elapsed, eta);
  if (!isatty(STDERR_FILENO)) std::fputc('\n', stderr);
  std::fflush(stderr);
}

void Progress::finish() const {
  if (enabled_) std::fputc('\n', stderr);
}

}  // namespace oitbench
