#include "oit/reference/image_compare.hpp"

#include <algorithm>
#include <cmath>

namespace oitbench::oit {

ApproxError approx_error(const std::vector<float>& rgb, const std::vector<double>& ref) {
  ApproxError e;
  double sum = 0;
  size_t off = 0, pixels = ref.size() / 3;
  for (size_t p = 0; p < pixels; ++p) {
    bool bad = false;
    for (int k = 0; k < 3; ++k) {
      double d = std::abs(static_cast<double>(rgb[p * 3 + k]) - ref[p * 3 + k]);
      if (!std::isfinite(d)) d = 1.0;  // a NaN counts as fully wrong here; finiteness is checked apart
      sum += d * d;
      e.max_abs_error = std::max(e.max_abs_error, d);
      bad |= d > 1.0 / 255.0;
    }
    off += bad;
  }
  e.rmse = pixels ? std::sqrt(sum / (pixels * 3.0)) : 0.0;
  e.psnr = e.rmse > 0 ? 20.0 * std::log10(1.0 / e.rmse) : 999.0;
  e.frac_pixels_off = pixels ? static_cast<double>(off) / pixels : 0.0;
  return e;
}

ImageRange image_range(const std::vector<float>& image, int channels) {
  ImageRange r;
  for (size_t i = 0; i + channels <= image.size(); i += channels) {
    bool out = false;
    for (int k = 0; k < 3; ++k) {
      float v = image[i + k];
      if (!std::isfinite(v))
        ++r.nonfinite;
      else
        out |= v < 0.0f || v > 1.0f;
    }
    r.out_of_range_pixels += out;
  }
  return r;
}

ImageError compare_with_reference(const std::vector<float>& rgba, const std::vector<double>& ref,
                                  const ListStats& stats, const Backdrop& backdrop, int width, double tolerance) {
  ImageError e;
  double sum_sq = 0;
  size_t pixels = ref.size() / 3;
  for (size_t p = 0; p < pixels; ++p) {
    const float* g = &rgba[p * 4];
    bool covered = stats.depth[p] > 0;
    if (g[3] != (covered ? 1.0f : 0.0f)) ++e.visit_errors;
    // Equal depths are compared too: every resolve breaks depth ties by colour bits, like the reference.
    glm::dvec3 got = g[3] == 0.0f ? glm::dvec3(backdrop.at(p)) : glm::dvec3(g[0], g[1], g[2]);
    double worst = 0;
    for (int k = 0; k < 3; ++k) {
      double d = std::abs(got[k] - ref[p * 3 + k]);
      if (std::isnan(d)) d = std::numeric_limits<double>::infinity();  // std::max would drop a NaN
      worst = std::max(worst, d);
      sum_sq += d * d;
    }
    e.max_abs_error = std::max(e.max_abs_error, worst);
    if (worst > tolerance) {
      if (e.bad_pixels++ == 0) {
        char buf[200];
        std::snprintf(buf, sizeof buf, "pixel (%zu,%zu): got (%.4f,%.4f,%.4f) resolved %gx, reference (%.4f,%.4f,%.4f)",
                      p % width, p / width, got[0], got[1], got[2], g[3], ref[p * 3], ref[p * 3 + 1], ref[p * 3 + 2]);
        e.first_bad = buf;
      }
    }
  }
  e.rmse = pixels ? std::sqrt(sum_sq / (pixels * 3.0)) : 0.0;
  return e;
}

Flicker flicker_of(const std::vector<std::vector<float>>& frames) {
  Flicker f;
  if (frames.size() < 2) return f;
  const size_t k = frames.size(), n = frames[0].size();
  for (size_t i = 0; i + 2 < n; i += 3) {
    double var_px = 0;
    for (int c = 0; c < 3; ++c) {
      double mean = 0, sq = 0;
      for (const auto& fr : frames) mean += fr[i + c];
      mean /= k;
      for (const auto& fr : frames) sq += (fr[i + c] - mean) * (fr[i + c] - mean);
      var_px += sq / k / 3.0;
    }
    f.mean += var_px;
    f.peak = std::max(f.peak, var_px);
    f.changed += var_px > 0;
  }
  f.mean /= static_cast<double>(n / 3);
  return f;
}

}  // namespace oitbench::oit
