#pragma once
// The metric columns the OIT cases (exact, approximate) and the lines experiment share, declared
// once: what an image's error against the exact composite is, and how many fragments a view has.
#include <vector>

#include "core/schema.hpp"

namespace oitbench::oit {

// Error of an image against the exact reference composite (double precision).
inline std::vector<MetricSpec> image_error_metrics() {
  using T = ValueType;
  return {{"rmse", T::Number, "", "root mean square error over every channel of every pixel, colours in [0, 1]"},
          {"psnr", T::Number, "dB", "peak signal-to-noise ratio, 20 log10(1 / rmse); 999 for an exact image"},
          {"max_abs_error", T::Number, "", "largest absolute error of a channel"},
          {"frac_pixels_off", T::Number, "", "fraction of pixels with a channel more than 1/255 off"},
          {"nonfinite", T::Integer, "", "channel values that are NaN or infinite"},
          {"out_of_range_pixels", T::Integer, "",
           "pixels with a finite colour channel outside [0, 1] (the PFM from render keeps them)"}};
}

// What the captured view holds.
inline std::vector<MetricSpec> fragment_metrics() {
  using T = ValueType;
  return {{"polygons", T::Integer, "", "primitives drawn per capture (triangles plus line segments)"},
          {"total_fragments", T::Integer, "", "fragments captured in the view"},
          {"peak_depth", T::Integer, "", "most fragments in one pixel"},
          {"mean_depth", T::Number, "", "fragments per covered pixel"}};
}

// Which library sort a case ran (shaders/sorts/): a micro-benchmark and a resolve that name the
// same value ran the same code.
inline MetricSpec sort_source_metric() {
  return {"sort_source", ValueType::Text, "",
          "the shaders/sorts/ file(s) the case's sort ran, each as PATH@FNV-1a "
          "of its text, joined by +; empty where no library sort ran"};
}

}  // namespace oitbench::oit
