#include "viewer/rolling_medians.hpp"

#include <algorithm>

namespace oitbench::viewer {

namespace {
double median_of(const std::deque<double>& d) {
  if (d.empty()) return 0;
  std::vector<double> v(d.begin(), d.end());
  auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  if (v.size() % 2) return *mid;
  return (*mid + *std::max_element(v.begin(), mid)) / 2;
}
}  // namespace

void RollingMedians::add(const std::string& name, double value) {
  auto it = std::find_if(series_.begin(), series_.end(), [&](const auto& s) { return s.first == name; });
  if (it == series_.end()) it = series_.insert(series_.end(), {name, {}});
  it->second.push_back(value);
  if (it->second.size() > window_) it->second.pop_front();
}

std::vector<std::pair<std::string, double>> RollingMedians::medians() const {
  std::vector<std::pair<std::string, double>> out;
  for (const auto& [name, values] : series_) out.emplace_back(name, median_of(values));
  return out;
}

double RollingMedians::median(const std::string& name) const {
  for (const auto& [n, values] : series_)
    if (n == name) return median_of(values);
  return 0;
}

size_t RollingMedians::samples(const std::string& name) const {
  for (const auto& [n, values] : series_)
    if (n == name) return values.size();
  return 0;
}

}  // namespace oitbench::viewer
