#include "core/phases.hpp"

#include <cstdio>

namespace oitbench {

const char* phase_name(Phase p) {
  switch (p) {
    case Phase::Scene:
      return "scene";
    case Phase::Compile:
      return "compile";
    case Phase::Pool:
      return "pool";
    case Phase::Warmup:
      return "warmup";
    case Phase::Samples:
      return "samples";
    case Phase::Readback:
      return "readback";
    case Phase::Reference:
      return "reference";
    case Phase::Validate:
      return "validate";
    case Phase::Other:
      return "other";
  }
  return "?";
}

std::string phase_column(Phase p) { return std::string("phase_") + phase_name(p) + "_s"; }

double PhaseTimes::total() const {
  double s = 0;
  for (double v : seconds) s += v;
  return s;
}

PhaseTimes& PhaseTimes::operator+=(const PhaseTimes& o) {
  for (size_t i = 0; i < seconds.size(); ++i) seconds[i] += o.seconds[i];
  return *this;
}

void PhaseClock::charge() {
  const auto now = Clock::now();
  if (times_) (*times_)[phase_] += std::chrono::duration<double>(now - since_).count();
  since_ = now;
}

void PhaseClock::attach(PhaseTimes* times, Phase p) {
  charge();
  times_ = times;
  phase_ = p;
}

Phase PhaseClock::switch_to(Phase p) {
  charge();
  const Phase was = phase_;
  phase_ = p;
  return was;
}

std::string RunAccount::summary_line(double wall_s) const {
  const PhaseTimes& c = cases;
  const double validation = c[Phase::Readback] + c[Phase::Reference] + c[Phase::Validate];
  const double scene = c[Phase::Scene] + c[Phase::Pool];
  const double known = c[Phase::Samples] + c[Phase::Compile] + c[Phase::Warmup] + validation + scene;
  const double other = wall_s - known;  // start, writing, children's start, the cases' own remainder, the end
  auto part = [&](const char* name, double s) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "%s %.1f s (%.0f%%)", name, s, wall_s > 0 ? 100.0 * s / wall_s : 0.0);
    return std::string(buf);
  };
  char tail[160];
  std::snprintf(tail, sizeof tail, " [start %.1f s, writing %.1f s, isolated cases' start %.1f s]", start_s, write_s,
                child_start_s);
  char head[64];
  std::snprintf(head, sizeof head, "oitbench: time %.1f s: ", wall_s);
  return head + part("timed samples", c[Phase::Samples]) + ", " + part("compile", c[Phase::Compile]) + ", " +
         part("warm-up", c[Phase::Warmup]) + ", " + part("reference+validation", validation) + ", " +
         part("scene", scene) + ", " + part("other", other) + tail;
}

}  // namespace oitbench
