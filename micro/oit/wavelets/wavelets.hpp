#pragma once
// WOIT, wavelet order-independent transparency (Aizenshtein, Smal, McGuire, "Wavelet Transparency",
// arXiv 2201.00094, 2022), a case of the oit experiment beside MBOIT (moments.hpp) and built the same
// way: an additive pass projects each fragment's absorbance -ln(1 - alpha), a Dirac pulse at its warped
// depth, onto a wavelet basis of `wavelet_coeffs` functions per pixel; a second additive pass weights
// each fragment by exp(-A(z)), A the integral of the reconstructed absorbance density up to the
// fragment's depth; a resolve normalises, the zeroth (scaling) coefficient being the total absorbance
// (wavelet_case.cpp, shaders/wavelets/). Validated against a double-precision CPU model of the same
// computation (wavelet_model.hpp); its error against the exact composite is data.
#include <glm/glm.hpp>
#include <memory>
#include <vector>

#include "core/registry.hpp"
#include "oit/oit_case.hpp"

namespace oitbench::oit {

// WOIT's variant. Haar: coefficient 0 is the scaling function (1 on [0, 1)), coefficient i >= 1 the
// wavelet psi_{j,k} with j = floor(log2 i), k = i - 2^j, orthonormal (2^(j/2) and -2^(j/2) on the
// halves of [k 2^-j, (k + 1) 2^-j)). N coefficients span the functions constant on N equal depth
// cells, so the reconstructed absorbance rises linearly across the cell of each fragment.
// Cosine (a smooth comparison basis, not a wavelet: the community code's Fourier basis in its
// half-range form): coefficient 0 is 1, coefficient k >= 1 is sqrt(2) cos(pi k x), orthonormal on [0, 1).
enum class WaveletBasis { Haar, Cosine };

struct WoitSettings {
  WaveletBasis basis = WaveletBasis::Haar;
  int coeffs = 16;                    // 8, 16, 32
  bool half_truncates = false;        // 16-bit: the blender rounds sums toward zero (probed per driver)
  int bits = 32;                      // storage of the coefficients: 32 (RGBA32F) or 16 (RGBA16F)
  glm::vec2 near_far{0.1f, 10.f};     // the projection's planes (window depth back to view depth)
  glm::vec2 depth_range{0.1f, 10.f};  // the view depths the log warp maps to [0, 1]: the geometry's
};

// The parameters WOIT adds to the oit experiment.
std::vector<ParamSpec> wavelet_params();

std::unique_ptr<OitCase> make_woit_case(const ParamSet& p, CaseContext& ctx);

}  // namespace oitbench::oit
