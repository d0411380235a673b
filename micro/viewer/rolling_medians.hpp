#pragma once
// Per-pass times on screen: the median of each pass over the last frames, so one slow frame (a
// JIT, the hypervisor) does not make the numbers jump.
#include <cstddef>
#include <deque>
#include <string>
#include <utility>
#include <vector>

namespace oitbench::viewer {

class RollingMedians {
 public:
  explicit RollingMedians(size_t window = 30) : window_(window) {}
  void add(const std::string& name, double value);
  void clear() { series_.clear(); }
  // (name, median) in the order the names first appeared.
  std::vector<std::pair<std::string, double>> medians() const;
  double median(const std::string& name) const;  // 0 when never added
  size_t samples(const std::string& name) const;

 private:
  size_t window_;
  std::vector<std::pair<std::string, std::deque<double>>> series_;
};

}  // namespace oitbench::viewer
