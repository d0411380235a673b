// The time account's bookkeeping (core/phases.hpp): one phase at a time, nested stretches pause the
// enclosing phase, and the phases add up to the time the clock was attached.
#include "core/phases.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

namespace oitbench {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }
void busy(double ms) { std::this_thread::sleep_for(std::chrono::duration<double, std::milli>(ms)); }

TEST(Phases, NestedStretchesPauseTheEnclosingPhaseAndTheSumIsTheAttachedTime) {
  PhaseClock clock;
  PhaseTimes t;
  const auto before = Clock::now();
  clock.attach(&t, Phase::Validate);
  const auto attached = Clock::now();
  busy(2);
  {
    PhaseClock::Scope reading(&clock, Phase::Readback);
    EXPECT_EQ(clock.current(), Phase::Readback);
    busy(2);
    {
      PhaseClock::Scope referencing(&clock, Phase::Reference);
      busy(2);
    }
    EXPECT_EQ(clock.current(), Phase::Readback);
    reading.end();
    EXPECT_EQ(clock.current(), Phase::Validate);
  }  // an ended scope's destructor changes nothing
  EXPECT_EQ(clock.current(), Phase::Validate);
  busy(2);
  const double inner = seconds_since(attached);
  clock.attach(nullptr, Phase::Other);
  const double outer = seconds_since(before);
  for (Phase p : {Phase::Validate, Phase::Readback, Phase::Reference}) EXPECT_GT(t[p], 0) << phase_name(p);
  for (Phase p : {Phase::Scene, Phase::Compile, Phase::Pool, Phase::Warmup, Phase::Samples, Phase::Other})
    EXPECT_EQ(t[p], 0) << phase_name(p);
  EXPECT_GE(t.total(), inner);
  EXPECT_LE(t.total(), outer);
  busy(1);  // detached: charged nowhere
  clock.attach(nullptr, Phase::Other);
  EXPECT_LE(t.total(), outer);
}

TEST(Phases, ANullClockScopeDoesNothing) {
  PhaseClock::Scope s(nullptr, Phase::Reference);
  s.end();
}

TEST(Phases, ColumnsAndTheSummaryLine) {
  EXPECT_EQ(phase_column(Phase::Samples), "phase_samples_s");
  EXPECT_EQ(phase_column(Phase::Reference), "phase_reference_s");
  RunAccount a;
  a.start_s = 1;
  a.cases[Phase::Samples] = 6;
  a.cases[Phase::Compile] = 1;
  a.cases[Phase::Reference] = 1;
  a.cases[Phase::Scene] = 0.5;
  a.cases[Phase::Pool] = 0.5;
  const std::string line = a.summary_line(10);
  EXPECT_NE(line.find("time 10.0 s"), std::string::npos) << line;
  EXPECT_NE(line.find("timed samples 6.0 s (60%)"), std::string::npos) << line;
  EXPECT_NE(line.find("reference+validation 1.0 s (10%)"), std::string::npos) << line;
  EXPECT_NE(line.find("scene 1.0 s (10%)"), std::string::npos) << line;
  EXPECT_NE(line.find("other 1.0 s (10%)"), std::string::npos) << line;  // what the rest leaves of the wall time
  EXPECT_NE(line.find("start 1.0 s"), std::string::npos) << line;
}

}  // namespace
}  // namespace oitbench
