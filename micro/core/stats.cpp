#include "core/stats.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace oitbench {

double median_of(std::vector<double> v) {
  if (v.empty()) throw std::invalid_argument("median of an empty sample");
  const size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid), v.end());
  const double hi = v[mid];
  if (v.size() % 2 == 1) return hi;
  const double lo = *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid));
  return 0.5 * (lo + hi);
}

Summary summarize(const std::vector<double>& samples) {
  Summary s;
  s.n = samples.size();
  if (samples.empty()) return s;
  s.median = median_of(samples);
  std::vector<double> dev(samples.size());
  std::transform(samples.begin(), samples.end(), dev.begin(), [&](double x) { return std::fabs(x - s.median); });
  s.mad = median_of(dev);
  auto [mn, mx] = std::minmax_element(samples.begin(), samples.end());
  s.min = *mn;
  s.max = *mx;
  s.mean = std::accumulate(samples.begin(), samples.end(), 0.0) / static_cast<double>(s.n);
  if (s.n > 1) {
    double ss = 0;
    for (double x : samples) ss += (x - s.mean) * (x - s.mean);
    s.stddev = std::sqrt(ss / static_cast<double>(s.n - 1));
  }
  const double limit = s.mad > 0 ? 5.0 * s.mad : 0.05 * std::fabs(s.median);
  s.outliers = static_cast<size_t>(
      std::count_if(samples.begin(), samples.end(), [&](double x) { return std::fabs(x - s.median) > limit; }));
  return s;
}

}  // namespace oitbench
