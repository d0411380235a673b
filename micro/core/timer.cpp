#include "core/timer.hpp"

#include <stdexcept>

#include "core/interrupt.hpp"

namespace oitbench {

PassTimer::Scope::Scope(PassTimer& t, std::string name, bool cpu_work) : timer_(t), cpu_work_(cpu_work) {
  throw_if_stop_requested();  // Ctrl-C: the case ends between passes, not after its repetition
  if (t.in_pass_) throw std::logic_error("timed pass '" + name + "' started inside another pass");
  t.in_pass_ = true;
  index_ = t.samples_.size();
  t.samples_.push_back({std::move(name), 0, -1, cpu_work});
  const bool query = t.use_queries_ && !cpu_work;
  while (query && t.queries_.size() <= index_) t.queries_.push_back(gl::make_query(GL_TIME_ELAPSED));
  if (t.sync_ || cpu_work) glFinish();
  start_ = std::chrono::steady_clock::now();
  if (query) glBeginQuery(GL_TIME_ELAPSED, t.queries_[index_].get());
}

PassTimer::Scope::~Scope() {
  const bool query = timer_.use_queries_ && !cpu_work_;
  if (query) glEndQuery(GL_TIME_ELAPSED);
  if (timer_.sync_ && !cpu_work_) glFinish();
  auto end = std::chrono::steady_clock::now();
  timer_.samples_[index_].cpu_ms = std::chrono::duration<double, std::milli>(end - start_).count();
  timer_.in_pass_ = false;
}

void PassTimer::begin_repetition() { samples_.clear(); }

std::vector<PassSample> PassTimer::end_repetition() {
  if (use_queries_) {
    for (size_t i = 0; i < samples_.size(); ++i) {
      if (samples_[i].cpu_work) continue;
      GLuint64 ns = 0;
      GLint available = 0;
      // Unsynchronised passes may still be running: the caller's glFinish after the repetition
      // has drained them, so the result is there; ask for it only then.
      glGetQueryObjectiv(queries_[i].get(), GL_QUERY_RESULT_AVAILABLE, &available);
      if (available) {
        glGetQueryObjectui64v(queries_[i].get(), GL_QUERY_RESULT, &ns);
        samples_[i].gpu_ms = static_cast<double>(ns) * 1e-6;
      }
    }
  }
  return std::move(samples_);
}

}  // namespace oitbench
