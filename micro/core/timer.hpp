#pragma once
// Timing of GPU work, two clocks at once: the CPU clock around glFinish (the work really done,
// trusted on software renderers) and GL_TIME_ELAPSED queries (trusted on hardware drivers).
// A pass is a scope: `{ auto t = timer.pass("resolve"); draw(); }`.
#include <chrono>
#include <string>
#include <vector>

#include "gl/gl_objects.hpp"

namespace oitbench {

struct PassSample {
  std::string pass;
  double cpu_ms = 0;
  double gpu_ms = -1;  // < 0: no query result
};

class PassTimer {
 public:
  explicit PassTimer(bool use_queries) : use_queries_(use_queries) {}
  PassTimer(const PassTimer&) = delete;
  PassTimer& operator=(const PassTimer&) = delete;

  class Scope {
   public:
    Scope(PassTimer& t, std::string name);
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;
    ~Scope();

   private:
    PassTimer& timer_;
    size_t index_;
    std::chrono::steady_clock::time_point start_;
  };
  // Starts a timed pass: drains earlier work (glFinish) before the clock starts; the scope's end
  // waits for the pass's own work (glFinish) before the clock stops.
  [[nodiscard]] Scope pass(std::string name) { return Scope(*this, std::move(name)); }

  void begin_repetition();
  // Reads the query results of the repetition that just ended (their work is finished).
  std::vector<PassSample> end_repetition();

 private:
  bool use_queries_;
  bool in_pass_ = false;
  std::vector<PassSample> samples_;
  std::vector<gl::Query> queries_;  // one per pass of the repetition, reused across repetitions
};

}  // namespace oitbench
