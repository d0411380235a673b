#pragma once
// The CPU models of MBOIT and STOCHASTIC (moments.hpp), which a GPU image must match to be valid,
// and the checks both cases share (model difference, flicker). Each model computes what the
// technique's shaders compute, in double precision, from the fragments the case captured:
//   MBOIT       the moments summed in the order fragments reached the pixel and rounded to the
//               storage (float, or half after every addition), then shaders/moments/moment_math.glsl's
//               reconstruction in double;
//   STOCHASTIC  the same hash, the same coverage masks, the same per-sample depth and accumulation
//               tests on the fragments' MSAA coverage (stochastic_case.cpp captures it), so the model
//               is exact, not statistical.
#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "oit/capture/fragment_storage.hpp"
#include "oit/moments/moments.hpp"
#include "oit/reference/image_compare.hpp"
#include "oit/reference/reference.hpp"

namespace oitbench::oit {

// --- MBOIT ----------------------------------------------------------------------------------------
// Window depth -> view depth (near_far: the projection) -> log, scaled from depth_range to [-1, 1].
double moment_warp(float window_depth, glm::vec2 near_far, glm::vec2 depth_range);
// The transmittance the moments reconstruct at warped depth z (b0 and the raw sums as stored).
// `rebiased`: set where the moments needed a raised bias (moment_math.glsl, REBIAS_STEPS).
double moment_transmittance(double b0, const std::vector<double>& raw, double z, const MboitSettings& s,
                            bool* rebiased = nullptr);
// RGB per pixel (3 doubles), background where no fragment landed; `rebiased` counts the fragments
// whose transmittance needed a raised bias.
std::vector<double> mboit_model(const HostLists& lists, const Backdrop& background, const MboitSettings& s,
                                size_t* rebiased = nullptr);
// IEEE half precision, round to nearest even (the 16-bit targets' storage).
float round_to_half(float v);

// --- STOCHASTIC -----------------------------------------------------------------------------------
// One fragment as the MSAA coverage capture (shaders/stochastic/coverage.frag) records it.
struct CoverageFragment {
  unsigned pixel = 0;      // y * width + x
  unsigned primitive = 0;  // gl_PrimitiveID
  unsigned coverage = 0;   // gl_SampleMaskIn[0]
  unsigned colour = 0;     // packUnorm4x8, as every technique sees it
  float depth = 0;         // gl_FragCoord.z (written as gl_FragDepth for all its samples)
};
// shaders/stochastic/hash.glsl on the CPU: the frame's seed from the run's seed and frame number,
// and the coverage mask of a fragment (alpha byte) among `samples` MSAA samples in pass `pass`.
uint32_t stochastic_frame_seed(uint32_t run_seed, uint32_t frame);
uint32_t stochastic_mask(uint32_t frame_seed, uint32_t pass, uint32_t x, uint32_t y, uint32_t primitive,
                         uint32_t alpha_byte, uint32_t samples);
struct StochasticSetup {
  int width = 0, height = 0;
  int msaa_samples = 4;  // per pass
  int passes = 1;        // samples_per_pixel = msaa_samples * passes
  uint32_t frame_seed = 0;
  unsigned threads = 0;  // the model's CPU threads (0: every core); its result does not depend on it
};
// RGB per pixel; `centre` (the ordinary capture) gives the total transmittance pass's fragments. Pixels
// are independent: their rows are spread over the cores (core/parallel_rows.hpp).
std::vector<double> stochastic_model(const std::vector<CoverageFragment>& fragments, const HostLists& centre,
                                     const Backdrop& background, const StochasticSetup& s);

// --- Shared checks --------------------------------------------------------------------------------
struct ModelCheck {
  double max_diff = 0;
  size_t off = 0, nonfinite = 0, out_of_range = 0;
  std::string first_off;  // "pixel (x,y) channel c: GPU g, model m"
};
ModelCheck check_against_model(const std::vector<float>& rgb, const std::vector<double>& model, int width,
                               double tolerance);

}  // namespace oitbench::oit
