#include "oit/wavelets/wavelet_model.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <thread>

#include "oit/moments/moment_model.hpp"

namespace oitbench::oit {

namespace {

constexpr double kAbsorbanceMax = 10.0;  // wavelet_math.glsl's ABSORBANCE_MAX, as MBOIT's
constexpr double kLastBelowOne = 0.99999994;
constexpr int kMaxCoeffs = 32;
constexpr double kPi = 3.14159265358979323846;
constexpr double kSqrt2 = 1.41421356237309504880;

// A float as a half-float target keeps it when the blender truncates (round toward zero).
float truncate_to_half(float v) {
  if (!std::isfinite(v) || v == 0.0f) return v;
  float a = std::fabs(v), step = 5.9604644775390625e-08f;  // 2^-24: the subnormal halves' spacing
  if (a >= 6.103515625e-05f) {
    int e = 0;
    std::frexp(a, &e);  // a = m 2^e, m in [0.5, 1): 11 significant bits
    step = std::ldexp(1.0f, e - 11);
  }
  return std::copysign(std::min(std::trunc(a / step) * step, 65504.0f), v);
}

double absorbance_of(double alpha) {
  return alpha >= 1.0 ? kAbsorbanceMax : std::min(-std::log(1.0 - alpha), kAbsorbanceMax);
}

// Level j of the Haar basis: its cell [lo, lo + width) holding x, its height 2^(j/2).
struct HaarCell {
  double lo, width, height;
};
HaarCell haar_cell(double x, int level) {
  const double cells = std::ldexp(1.0, level);
  return {std::floor(x * cells) / cells, 1.0 / cells, std::sqrt(cells)};
}

}  // namespace

double wavelet_warp(float window_depth, glm::vec2 nf, glm::vec2 range) {
  double n = nf.x, f = nf.y;
  double view = n * f / (f - window_depth * (f - n));
  double x = (std::log(view) - std::log(range.x)) / (std::log(range.y) - std::log(range.x));
  return std::clamp(x, 0.0, kLastBelowOne);
}

void haar_contribution(double x, double absorbance, int n, double* out) {
  out[0] = absorbance;
  for (int level = 0; (1 << level) < n; ++level) {
    const HaarCell c = haar_cell(x, level);
    const int first = 1 << level, k = static_cast<int>(c.lo / c.width + 0.5);
    for (int i = first; i < 2 * first; ++i) out[i] = 0.0;
    out[first + k] = absorbance * (x < c.lo + 0.5 * c.width ? c.height : -c.height);
  }
}

double haar_absorbance(const double* coeffs, int n, double x) {
  double a = coeffs[0] * x;
  for (int level = 0; (1 << level) < n; ++level) {
    const HaarCell c = haar_cell(x, level);
    const int k = static_cast<int>(c.lo / c.width + 0.5);
    const double u = x - c.lo, half = 0.5 * c.width;  // the wavelet's integral: a tent over the cell
    a += coeffs[(1 << level) + k] * c.height * (u < half ? u : c.width - u);
  }
  return std::max(a, 0.0);
}

void cosine_contribution(double x, double absorbance, int n, double* out) {
  out[0] = absorbance;
  for (int k = 1; k < n; ++k) out[k] = absorbance * kSqrt2 * std::cos(kPi * k * x);
}

double cosine_absorbance(const double* coeffs, int n, double x) {
  double a = coeffs[0] * x;
  for (int k = 1; k < n; ++k) a += coeffs[k] * kSqrt2 * std::sin(kPi * k * x) / (kPi * k);
  return std::clamp(a, 0.0, std::max(coeffs[0], 0.0));
}

std::vector<double> woit_model(const HostLists& l, const Backdrop& bg, const WoitSettings& s) {
  const size_t pixels = l.heads.size();
  const int n = std::min(s.coeffs, kMaxCoeffs);
  auto store = [&](float v) { return s.bits != 16 ? v : s.half_truncates ? truncate_to_half(v) : round_to_half(v); };
  std::vector<double> out(pixels * 3);
  // Rows of pixels on every core: each pixel is independent.
  const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  auto rows = [&](unsigned part) {
    std::vector<ArrivedFragment> frags;
    std::array<double, kMaxCoeffs> contribution{}, coeffs{};
    std::array<float, kMaxCoeffs> sums{};
    for (size_t px = part; px < pixels; px += threads) {
      arrival_order(l, px, frags);
      // Pass 1: the coefficients as the blender sums them into the targets.
      sums.fill(0.0f);
      for (const auto& fr : frags) {
        const double x = wavelet_warp(fr.depth, s.near_far, s.depth_range), a = absorbance_of(fr.colour.a);
        if (s.basis == WaveletBasis::Cosine)
          cosine_contribution(x, a, n, contribution.data());
        else
          haar_contribution(x, a, n, contribution.data());
        for (int i = 0; i < n; ++i) sums[i] = store(sums[i] + static_cast<float>(contribution[i]));
      }
      for (int i = 0; i < n; ++i) coeffs[i] = sums[i];
      // Pass 2: each fragment weighted by the transmittance in front of its depth.
      glm::dvec4 acc(0.0);
      for (const auto& fr : frags) {
        const double x = wavelet_warp(fr.depth, s.near_far, s.depth_range);
        double t = std::exp(-(s.basis == WaveletBasis::Cosine ? cosine_absorbance(coeffs.data(), n, x)
                                                              : haar_absorbance(coeffs.data(), n, x)));
        acc += glm::dvec4(glm::dvec3(fr.colour) * static_cast<double>(fr.colour.a) * t, fr.colour.a * t);
      }
      // Resolve: the zeroth coefficient is the total absorbance.
      double total = std::exp(-coeffs[0]);
      glm::dvec3 behind(bg.at(px)), c = acc.a > 0 ? glm::dvec3(acc) / acc.a * (1.0 - total) + behind * total : behind;
      for (int k = 0; k < 3; ++k) out[px * 3 + k] = c[k];
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 0; t < threads; ++t) pool.emplace_back(rows, t);
  for (auto& t : pool) t.join();
  return out;
}

}  // namespace oitbench::oit
