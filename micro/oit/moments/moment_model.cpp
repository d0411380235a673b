#include "oit/moments/moment_model.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <complex>
#include <sstream>
#include <thread>

#include "core/parallel_rows.hpp"
#include "oit/case_support.hpp"

namespace oitbench::oit {

namespace {

using Complex = std::complex<double>;
constexpr double kPi = 3.14159265358979323846;
constexpr double kAbsorbanceMax = 10.0;
constexpr double kWrappingZone = 0.1 * kPi;
constexpr int kRootIterations = 200;
constexpr int kRebiasSteps = 3;  // moment_math.glsl's REBIAS_STEPS

double absorbance_of(double alpha) {
  return alpha >= 1.0 ? kAbsorbanceMax : std::min(-std::log(1.0 - alpha), kAbsorbanceMax);
}

double moment_phase(double z) { return (z + 1.0) * (kPi - 0.5 * kWrappingZone); }
double circle_parameter(Complex p) {
  double r = std::abs(p.imag()) - std::abs(p.real());
  r = p.real() < 0.0 ? 2.0 - r : r;
  return p.imag() < 0.0 ? 6.0 - r : r;
}
double wrapping_weight(double reference, double root) {
  double zone_begin = circle_parameter(std::polar(1.0, 2.0 * kPi - kWrappingZone));
  double scale = 1.0 / (7.0 - zone_begin);
  return (root < reference ? 1.0 : 0.0) + std::clamp(root * scale + 1.0 - 7.0 * scale, 0.0, 1.0);
}

const std::vector<double>& power_bias_vector(int moments) {
  // The paper's bias vectors for float storage (its published HLSL, as ported by PixelSyncOIT).
  static const std::vector<double> four = {0, 0.375, 0, 0.375}, six = {0, 0.48, 0, 0.451, 0, 0.45},
                                   eight = {0, 0.75, 0, 0.67666666666666664, 0, 0.63, 0, 0.60030303030303034};
  return moments == 4 ? four : moments == 6 ? six : eight;
}

}  // namespace

float mboit_paper_bias(MomentKind kind, int moments, int bits) {
  // Münstermann et al. 2018, the moment bias per variant (power: 4/6/8 moments; trigonometric:
  // 2/3/4 complex moments, i.e. 4/6/8 reals), single precision and 16 bits.
  const bool half = bits == 16;
  if (kind == MomentKind::Power) {
    if (moments == 4) return half ? 6e-5f : 5e-7f;
    if (moments == 6) return half ? 6e-4f : 5e-6f;
    return half ? 2.5e-3f : 5e-5f;
  }
  if (moments == 4) return half ? 4e-4f : 4e-7f;
  if (moments == 6) return half ? 6.5e-4f : 8e-7f;
  return half ? 8.5e-4f : 1.5e-6f;
}

double moment_warp(float window_depth, glm::vec2 nf, glm::vec2 range) {
  double n = nf.x, f = nf.y;
  double view = n * f / (f - window_depth * (f - n));
  return (std::log(view) - std::log(range.x)) / (std::log(range.y) - std::log(range.x)) * 2.0 - 1.0;
}

float round_to_half(float v) {
  if (!std::isfinite(v) || v == 0.0f) return v;
  float a = std::fabs(v);
  if (a >= 65520.0f) return std::copysign(INFINITY, v);
  float step;
  if (a < 6.103515625e-05f) {
    step = 5.9604644775390625e-08f;  // 2^-24: the subnormal halves' spacing
  } else {
    int e = 0;
    std::frexp(a, &e);  // a = m 2^e, m in [0.5, 1): 11 significant bits
    step = std::ldexp(1.0f, e - 11);
  }
  return std::copysign(std::nearbyint(a / step) * step, v);
}

double moment_transmittance(double b0, const std::vector<double>& raw, double z, const MboitSettings& s,
                            bool* rebiased) {
  const int order = s.moments / 2;
  const bool trig = s.kind == MomentKind::Trigonometric;
  const double bias = s.bias;
  std::array<Complex, 9> m{};  // fixed sizes: this runs once per fragment
  Complex point = trig ? std::polar(1.0, moment_phase(z)) : Complex(z);
  std::array<std::array<Complex, 6>, 5> a{};
  double b = bias;
  for (int attempt = 0; attempt <= kRebiasSteps; ++attempt, b = std::min(b * 10.0, 1.0)) {
    m[0] = 1.0;
    if (trig) {
      for (int k = 1; k <= order; ++k) m[k] = Complex(raw[2 * k - 2], raw[2 * k - 1]) / b0 * (1.0 - b);
    } else {
      const auto& bv = power_bias_vector(s.moments);
      for (int k = 1; k <= s.moments; ++k) m[k] = (1.0 - b) * (raw[k - 1] / b0) + b * bv[k - 1];
    }
    Complex e = 1.0;
    for (int i = 0; i <= order; ++i) {
      for (int j = 0; j <= order; ++j) a[i][j] = trig ? (i >= j ? m[i - j] : std::conj(m[j - i])) : m[i + j];
      a[i][order + 1] = e;
      e *= point;
    }
    bool definite = true;
    for (int k = 0; k <= order; ++k) {
      definite = definite && a[k][k].real() > 0.0;
      for (int i = k + 1; i <= order; ++i) {
        Complex f = a[i][k] / a[k][k];
        for (int j = k; j <= order + 1; ++j) a[i][j] -= f * a[k][j];
      }
    }
    if (rebiased) *rebiased = attempt > 0;
    if (definite) break;
  }
  std::array<Complex, 5> c{};
  for (int i = order; i >= 0; --i) {
    Complex sum = a[i][order + 1];
    for (int j = i + 1; j <= order; ++j) sum -= a[i][j] * c[j];
    c[i] = sum / a[i][i];
  }
  std::array<Complex, 5> q{};
  for (int k = 0; k <= order; ++k) q[k] = trig ? std::conj(c[k]) / std::conj(c[order]) : c[k] / c[order];
  std::array<Complex, 5> x{};
  x[0] = point;
  Complex seed(0.4, 0.9);
  for (int k = 1; k <= order; ++k, seed *= Complex(0.4, 0.9)) x[k] = seed;
  for (int it = 0; it < kRootIterations; ++it) {
    double moved = 0;
    for (int k = 1; k <= order; ++k) {
      Complex value = q[order], denominator = 1.0;
      for (int j = order - 1; j >= 0; --j) value = value * x[k] + q[j];
      for (int j = 1; j <= order; ++j)
        if (j != k) denominator *= x[k] - x[j];
      if (std::norm(denominator) > 0.0) {
        Complex step = value / denominator;
        x[k] -= step;
        moved = std::max(moved, std::norm(step));
      }
    }
    if (moved < 1e-30) break;  // converged to double precision
  }
  std::array<Complex, 5> f{};
  f[0] = s.overestimation;
  if (trig) {
    double reference = circle_parameter(point);
    for (int k = 1; k <= order; ++k) {
      x[k] /= std::abs(x[k]);
      f[k] = wrapping_weight(reference, circle_parameter(x[k]));
    }
  } else {
    for (int k = 1; k <= order; ++k) {
      x[k] = x[k].real();
      f[k] = x[k].real() < z ? 1.0 : 0.0;
    }
  }
  for (int j = 1; j <= order; ++j)
    for (int i = order; i >= j; --i) f[i] = (f[i] - f[i - 1]) / (x[i] - x[i - j]);
  std::array<Complex, 5> p{};
  p[0] = f[order];
  for (int k = order - 1; k >= 0; --k) {
    for (int j = order; j >= 1; --j) p[j] = p[j - 1] - p[j] * x[k];
    p[0] = f[k] - p[0] * x[k];
  }
  double absorbance = 0;
  for (int k = 0; k <= order; ++k) absorbance += (p[k] * m[k]).real();
  return std::clamp(std::exp(-b0 * absorbance), 0.0, 1.0);
}

std::vector<double> mboit_model(const HostLists& l, const Backdrop& bg, const MboitSettings& s, size_t* rebiased) {
  const size_t pixels = l.heads.size();
  const int n = s.moments;
  const bool trig = s.kind == MomentKind::Trigonometric;
  auto store = [&](float v) { return s.bits == 16 ? round_to_half(v) : v; };
  std::vector<double> out(pixels * 3);
  // Rows of pixels on every core: each pixel is independent.
  const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  std::vector<size_t> raised_count(threads, 0);
  auto rows = [&](unsigned part) {
    std::vector<ArrivedFragment> frags;
    std::vector<double> contribution(n), raw(n);
    std::vector<float> sums(n);
    for (size_t px = part; px < pixels; px += threads) {
      arrival_order(l, px, frags);
      // Pass 1: the moments as the blender sums them into the targets.
      float b0 = 0;
      std::fill(sums.begin(), sums.end(), 0.0f);
      for (const auto& fr : frags) {
        double a = absorbance_of(fr.colour.a), z = moment_warp(fr.depth, s.near_far, s.depth_range);
        if (trig) {
          Complex pk = std::polar(1.0, moment_phase(z)), p = pk;
          for (int k = 0; k < n / 2; ++k, pk *= p)
            contribution[2 * k] = pk.real() * a, contribution[2 * k + 1] = pk.imag() * a;
        } else {
          double zk = z;
          for (int k = 0; k < n; ++k, zk *= z) contribution[k] = zk * a;
        }
        b0 = store(b0 + static_cast<float>(a));
        for (int k = 0; k < n; ++k) sums[k] = store(sums[k] + static_cast<float>(contribution[k]));
      }
      for (int k = 0; k < n; ++k) raw[k] = sums[k];
      // Pass 2: each fragment weighted by the reconstructed transmittance at its depth.
      glm::dvec4 acc(0.0);
      for (const auto& fr : frags) {
        bool raised = false;
        double t =
            b0 > 0 ? moment_transmittance(b0, raw, moment_warp(fr.depth, s.near_far, s.depth_range), s, &raised) : 1.0;
        raised_count[part] += raised;
        acc += glm::dvec4(glm::dvec3(fr.colour) * static_cast<double>(fr.colour.a) * t, fr.colour.a * t);
      }
      // Resolve.
      double total = std::exp(-static_cast<double>(b0));
      glm::dvec3 behind(bg.at(px)), c = acc.a > 0 ? glm::dvec3(acc) / acc.a * (1.0 - total) + behind * total : behind;
      for (int k = 0; k < 3; ++k) out[px * 3 + k] = c[k];
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 0; t < threads; ++t) pool.emplace_back(rows, t);
  for (auto& t : pool) t.join();
  if (rebiased)
    for (size_t r : raised_count) *rebiased += r;
  return out;
}

// --- STOCHASTIC -------------------------------------------------------------------------------------

namespace {
uint32_t pcg(uint32_t v) {  // PCG-RXS-M-XS (Jarzynski & Olano 2020's hash for GPUs)
  uint32_t state = v * 747796405u + 2891336453u;
  uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}
}  // namespace

uint32_t stochastic_frame_seed(uint32_t run_seed, uint32_t frame) { return pcg(run_seed ^ pcg(frame)); }

uint32_t stochastic_mask(uint32_t frame_seed, uint32_t pass, uint32_t x, uint32_t y, uint32_t primitive,
                         uint32_t alpha_byte, uint32_t samples) {
  uint32_t h = pcg(pcg(pcg(pcg(x) + y) + primitive) ^ (frame_seed + pass * 0x9E3779B9u));
  // k = floor(alpha * samples + u), u uniform in [0, 1): each sample covered with probability alpha.
  uint32_t k = (alpha_byte * samples * 65536u / 255u + (h & 0xFFFFu)) >> 16;
  uint32_t r = (h >> 16) % samples;
  uint32_t all = (1u << samples) - 1u, run = (1u << k) - 1u;
  return ((run << r) | (run >> (samples - r))) & all;
}

std::vector<double> stochastic_model(const std::vector<CoverageFragment>& fragments, const HostLists& centre,
                                     const Backdrop& bg, const StochasticSetup& s) {
  const size_t pixels = static_cast<size_t>(s.width) * s.height;
  const int S = s.msaa_samples;
  std::vector<std::vector<const CoverageFragment*>> by_pixel(pixels);
  for (const auto& f : fragments)
    if (f.pixel < pixels) by_pixel[f.pixel].push_back(&f);
  std::vector<double> out(pixels * 3);
  const size_t row = static_cast<size_t>(std::max(1, s.width));
  struct Scratch {  // each thread's
    std::vector<float> depth;
    std::vector<ArrivedFragment> frags;
  };
  std::vector<Scratch> scratch(parallel_row_threads((pixels + row - 1) / row, s.threads));
  for (auto& sc : scratch) sc.depth.resize(static_cast<size_t>(S));
  parallel_rows(pixels, row, s.threads, [&](unsigned thread, size_t px) {
    std::vector<float>& depth = scratch[thread].depth;
    std::vector<ArrivedFragment>& frags = scratch[thread].frags;
    const uint32_t x = static_cast<uint32_t>(px % s.width), y = static_cast<uint32_t>(px / s.width);
    glm::dvec4 acc(0.0);
    for (int pass = 0; pass < s.passes; ++pass) {
      std::fill(depth.begin(), depth.end(), 1.0f);
      for (const auto* f : by_pixel[px]) {
        uint32_t mask = f->coverage & stochastic_mask(s.frame_seed, pass, x, y, f->primitive, f->colour >> 24, S);
        for (int k = 0; k < S; ++k)
          if ((mask >> k & 1u) && f->depth < depth[k]) depth[k] = f->depth;
      }
      for (const auto* f : by_pixel[px]) {
        glm::dvec4 c(unpack_rgba8(f->colour));
        for (int k = 0; k < S; ++k)
          if ((f->coverage >> k & 1u) && f->depth <= depth[k]) acc += glm::dvec4(glm::dvec3(c) * c.a, c.a);
      }
    }
    acc /= static_cast<double>(S * s.passes);
    arrival_order(centre, px, frags);
    double total = 1.0;
    for (const auto& fr : frags) total *= 1.0 - fr.colour.a;
    glm::dvec3 behind(bg.at(px)), c = acc.a > 0 ? glm::dvec3(acc) * (1.0 - total) / acc.a + behind * total : behind;
    for (int k = 0; k < 3; ++k) out[px * 3 + k] = c[k];
  });
  return out;
}

// --- Shared checks ---------------------------------------------------------------------------------

ModelCheck check_against_model(const std::vector<float>& rgb, const std::vector<double>& model, int width,
                               double tolerance) {
  ModelCheck r;
  for (size_t i = 0; i < rgb.size() && i < model.size(); ++i) {
    if (!std::isfinite(rgb[i]))
      ++r.nonfinite;
    else if (rgb[i] < -1.0 / 255.0 || rgb[i] > 1.0 + 2.0 / 255.0)
      ++r.out_of_range;
    double d = std::abs(static_cast<double>(rgb[i]) - model[i]);
    if (!std::isfinite(d)) d = std::isfinite(rgb[i]) == std::isfinite(model[i]) ? 0.0 : 1.0;
    r.max_diff = std::max(r.max_diff, d);
    if (d > tolerance && r.off++ == 0) {
      size_t px = i / 3;
      r.first_off = "pixel (" + std::to_string(px % width) + "," + std::to_string(px / width) + ") channel " +
                    std::to_string(i % 3) + ": GPU " + fmt(rgb[i]) + ", model " + fmt(model[i]);
    }
  }
  return r;
}

}  // namespace oitbench::oit
