#pragma once
// Robust summary statistics of repeated timings (in the manner of nanobench and hyperfine).
#include <cstddef>
#include <vector>

namespace oitbench {

struct Summary {
  size_t n = 0;
  double median = 0, mad = 0;  // MAD: median absolute deviation from the median, unscaled
  double min = 0, max = 0, mean = 0;
  double stddev = 0;    // sample standard deviation (n-1); 0 for a single sample
  size_t outliers = 0;  // samples further than 5 MAD (or 5% when MAD is 0) from the median
};

double median_of(std::vector<double> values);  // mean of the two middle values for even counts
Summary summarize(const std::vector<double>& samples);

}  // namespace oitbench
