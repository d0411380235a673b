#include "core/timer.hpp"

#include <stdexcept>

namespace oitbench {

PassTimer::Scope::Scope(PassTimer& t, std::string name) : timer_(t) {
  if (t.in_pass_) throw std::logic_error("timed pass '" + name + "' started inside another pass");
  t.in_pass_ = true;
  index_ = t.samples_.size();
  t.samples_.push_back({std::move(name), 0, -1});
  if (t.use_queries_ && t.queries_.size() <= index_) t.queries_.push_back(gl::make_query(GL_TIME_ELAPSED));
  glFinish();
  start_ = std::chrono::steady_clock::now();
  if (t.use_queries_) glBeginQuery(GL_TIME_ELAPSED, t.queries_[index_].get());
}

PassTimer::Scope::~Scope() {
  if (timer_.use_queries_) glEndQuery(GL_TIME_ELAPSED);
  glFinish();
  auto end = std::chrono::steady_clock::now();
  timer_.samples_[index_].cpu_ms = std::chrono::duration<double, std::milli>(end - start_).count();
  timer_.in_pass_ = false;
}

void PassTimer::begin_repetition() { samples_.clear(); }

std::vector<PassSample> PassTimer::end_repetition() {
  if (use_queries_) {
    for (size_t i = 0; i < samples_.size(); ++i) {
      GLuint64 ns = 0;
      GLint available = 0;
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
