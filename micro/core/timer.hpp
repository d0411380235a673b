#pragma once
// Timing of GPU work, two clocks at once: the CPU clock around glFinish (the work really done,
// trusted on software renderers) and GL_TIME_ELAPSED queries (trusted on hardware drivers).
// A pass is a scope: `{ auto t = timer.pass("resolve"); draw(); }`. Work done on the CPU (a
// CPU resolve, a read-back) is a `cpu_pass`: timed by the CPU clock alone, whatever the primary
// clock, since a query around it would time no GL work.
//
// Synchronised (software renderers, or --sync-passes): every GL pass is bracketed by glFinish, so
// its CPU time is its work. Not synchronised (hardware drivers by default): GL passes are only
// bracketed by their queries and run back to back as a frame would; their CPU time is then the
// time to submit them, and only the query is their cost.
#include <chrono>
#include <string>
#include <vector>

#include "gl/gl_objects.hpp"

namespace oitbench {

struct PassSample {
  std::string pass;
  double cpu_ms = 0;
  double gpu_ms = -1;     // < 0: no query result
  bool cpu_work = false;  // a cpu_pass: the CPU clock is its only clock
};

class PassTimer {
 public:
  explicit PassTimer(bool use_queries, bool sync = true) : use_queries_(use_queries), sync_(sync) {}
  PassTimer(const PassTimer&) = delete;
  PassTimer& operator=(const PassTimer&) = delete;

  class Scope {
   public:
    Scope(PassTimer& t, std::string name, bool cpu_work);
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;
    ~Scope();

   private:
    PassTimer& timer_;
    size_t index_;
    bool cpu_work_;
    std::chrono::steady_clock::time_point start_;
  };
  // Starts a timed pass: drains earlier work (glFinish) before the clock starts; the scope's end
  // waits for the pass's own work (glFinish) before the clock stops.
  [[nodiscard]] Scope pass(std::string name) { return Scope(*this, std::move(name), false); }
  // Starts a pass of CPU work: earlier GL work is drained first (glFinish), then only the CPU clock runs.
  [[nodiscard]] Scope cpu_pass(std::string name) { return Scope(*this, std::move(name), true); }
  bool synchronised() const { return sync_; }

  void begin_repetition();
  // Reads the query results of the repetition that just ended (their work is finished).
  std::vector<PassSample> end_repetition();

 private:
  bool use_queries_;
  bool sync_;
  bool in_pass_ = false;
  std::vector<PassSample> samples_;
  std::vector<gl::Query> queries_;  // one per pass of the repetition, reused across repetitions
};

}  // namespace oitbench
