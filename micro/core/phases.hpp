#pragma once
// Where a case's wall time went outside its timed samples (issue 28's time account): the runner charges
// every second of a case's life to one phase at a time, and a case may name a finer phase for a stretch
// of its own work (`auto p = ctx.phase(Phase::Reference);`), which pauses the enclosing phase. Phases
// never overlap, so they add up to the case's wall time; `other` is the measured remainder (the runner's
// own work between phases: progress, the GPU state, the stopping rule). The run's start (process,
// context, plan) and the writing of rows are the run's, not a case's: RunAccount below.
#include <array>
#include <chrono>
#include <string>

namespace oitbench {

enum class Phase {
  Scene,      // preparing the case apart from compiling: scene build and upload, buffers, targets
  Compile,    // compiling and linking its programs (CaseContext::build), program-cache loads included
  Pool,       // sizing its storage: the count pass that sizes a fragment pool (or a capture and its re-renders)
  Warmup,     // untimed repetitions, and rounds the sample-size check took as warm-up
  Samples,    // the timed repetitions
  Readback,   // reading the result back for validation
  Reference,  // computing the CPU (or geometric) reference
  Validate,   // comparing with the reference, metrics, notes
  Other,      // the remainder
};
inline constexpr int kPhaseCount = static_cast<int>(Phase::Other) + 1;
inline constexpr Phase kAllPhases[] = {Phase::Scene,     Phase::Compile,  Phase::Pool,
                                       Phase::Warmup,    Phase::Samples,  Phase::Readback,
                                       Phase::Reference, Phase::Validate, Phase::Other};

const char* phase_name(Phase p);    // "scene", "compile", ...
std::string phase_column(Phase p);  // "phase_scene_s", ...

// Seconds per phase.
struct PhaseTimes {
  std::array<double, kPhaseCount> seconds{};
  double& operator[](Phase p) { return seconds[static_cast<size_t>(p)]; }
  double operator[](Phase p) const { return seconds[static_cast<size_t>(p)]; }
  double total() const;
  PhaseTimes& operator+=(const PhaseTimes& o);
};

// The one clock of a run: charges the time since its last switch to the phase it is in, of the
// PhaseTimes it is attached to (none: the time is charged nowhere).
class PhaseClock {
 public:
  using Clock = std::chrono::steady_clock;
  PhaseClock() = default;
  PhaseClock(const PhaseClock&) = delete;
  PhaseClock& operator=(const PhaseClock&) = delete;

  // From now on, time goes to `times`' phase `p` (nullptr: nowhere).
  void attach(PhaseTimes* times, Phase p);
  // Switches phase within the attached times; returns the phase it was in.
  Phase switch_to(Phase p);
  Phase current() const { return phase_; }

  // A stretch of work in phase `p`; the phase it interrupted resumes at its end. A null clock: no-op.
  class Scope {
   public:
    Scope(PhaseClock* clock, Phase p) : clock_(clock), previous_(clock ? clock->switch_to(p) : p) {}
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;
    ~Scope() { end(); }
    // Ends the stretch early (the destructor then does nothing).
    void end() {
      if (clock_) clock_->switch_to(previous_);
      clock_ = nullptr;
    }

   private:
    PhaseClock* clock_;
    Phase previous_;
  };

 private:
  void charge();
  PhaseTimes* times_ = nullptr;
  Phase phase_ = Phase::Other;
  Clock::time_point since_ = Clock::now();
};

// The run's own account: its start (process start to the first case: context, GL strings, program
// cache, output files, plan), the writing of rows, cases run in child processes (their rows' phases,
// and the rest of the child's life as its start), the cases' phases summed, and its end.
struct RunAccount {
  double start_s = 0, write_s = 0, child_start_s = 0;
  PhaseTimes cases;
  // One line: the shares of the run's wall time (timed samples, compile, warm-up, reference and
  // validation, scene, other), seconds and %; `wall_s` the run's wall time, from which `other` is
  // what the rest leaves (never a guess).
  std::string summary_line(double wall_s) const;
};

}  // namespace oitbench
