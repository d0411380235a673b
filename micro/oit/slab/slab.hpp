#pragma once
// SLAB, stochastic layered alpha blending (Wyman, "Exploring and Expanding the Continuum of OIT
// Algorithms", HPG 2016, section 5; the SIGGRAPH 2016 talk "Stochastic Layered Alpha Blending"), a
// technique of the oit experiment beside STOCHASTIC: each pixel keeps slab_layers layers (depth, a
// coverage mask of samples_per_pixel samples, an RGB colour) in depth order, each fragment's mask
// drawn from its alpha by STOCHASTIC's hash (shaders/stochastic/hash.glsl). One geometry pass
// inserts every fragment under a per-pixel spinlock (shaders/slab/insert.frag), a resolve averages
// the samples (shaders/slab/resolve.frag). slab_layers >= samples_per_pixel never merges: each sample
// shows the nearest fragment covering it, stochastic transparency's estimate from the same masks;
// fewer layers merge the two farthest, down to one layer that blends everything behind the nearest.
// Validated against slab_model, the same masks and the same insertions on the CPU (exact, not
// statistical); the error against the exact composite is data.
#include <cstdint>
#include <memory>
#include <vector>

#include "core/registry.hpp"
#include "oit/moments/moment_model.hpp"
#include "oit/oit_case.hpp"

namespace oitbench::oit {

// The parameter SLAB adds to the oit experiment (samples_per_pixel it shares with STOCHASTIC).
std::vector<ParamSpec> slab_params();
std::unique_ptr<OitCase> make_slab_case(const ParamSet& p, CaseContext& ctx);

struct SlabSetup {
  int width = 0, height = 0;
  int layers = 4;   // slab_layers
  int samples = 8;  // samples_per_pixel: 4, 8, 16, 32
  uint32_t frame_seed = 0;
  unsigned threads = 0;  // the model's CPU threads (0: every core); its result does not depend on it
};
// One layer as shaders/slab/layers.glsl keeps it.
struct SlabLayer {
  float depth = 0;
  uint32_t mask = 0;    // the samples where this layer is the nearest surface; 0: empty
  uint32_t colour = 0;  // packUnorm4x8 of the RGB, alpha byte 0
};
// shaders/slab/layers.glsl on the CPU: a fragment's mask, and its insertion into a pixel's layers.
uint32_t slab_mask(uint32_t frame_seed, uint32_t x, uint32_t y, uint32_t primitive, uint32_t alpha_byte,
                   uint32_t samples);
void slab_insert(std::vector<SlabLayer>& layers, int max_layers, SlabLayer fragment);
// RGB per pixel: the fragments (each pixel's in the order they arrived) inserted, then resolved.
std::vector<double> slab_model(const std::vector<CoverageFragment>& fragments, const Backdrop& background,
                               const SlabSetup& s);

}  // namespace oitbench::oit
