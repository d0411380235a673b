#pragma once
// Two approximate techniques that need no per-pixel arrays, cases of the oit experiment beside
// approx.hpp's:
//   MBOIT       moment-based OIT (Münstermann, Krumpen, Klein, Peters, i3D 2018): an additive pass
//               sums the absorbance's power or trigonometric moments per pixel (moment_case.cpp,
//               shaders/moments/), a second additive pass weights each fragment by the transmittance
//               the moments reconstruct at its depth, a resolve normalises.
//   STOCHASTIC  stochastic transparency (Enderton, Sintorn, Shirley, Luebke, i3D 2010): alpha becomes
//               an MSAA coverage mask drawn from a seeded hash, a depth pass keeps the nearest
//               covering surface per sample, an accumulation pass counts each fragment's visible
//               samples, a total-alpha pass and the alpha correction finish (stochastic_case.cpp,
//               shaders/stochastic/).
// Both are validated against a double-precision CPU model of the same computation
// (moment_model.hpp); their error against the exact composite is data.
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

#include "core/registry.hpp"
#include "oit/capture/fragment_storage.hpp"
#include "oit/oit_case.hpp"
#include "oit/scene/gpu_mesh.hpp"
#include "oit/scene/scene.hpp"
#include "oit/scene/scene_passes.hpp"

namespace oitbench::oit {

enum class MomentKind { Power, Trigonometric };

// MBOIT's variant. `moments` counts the real numbers stored beside the zeroth moment (the paper's
// NUM_MOMENTS): power moments b1..b_n, or n/2 complex trigonometric moments.
struct MboitSettings {
  MomentKind kind = MomentKind::Power;
  int moments = 4;                    // 4, 6, 8
  int bits = 32;                      // storage of the moments: 32 (R/RG/RGBA32F) or 16 (.. 16F)
  float bias = 5e-7f;                 // mboit_paper_bias(kind, moments, bits)
  float overestimation = 0.25f;       // beta: the weight of a fragment's own depth
  glm::vec2 near_far{0.1f, 10.f};     // the projection's planes (window depth back to view depth)
  glm::vec2 depth_range{0.1f, 10.f};  // the view depths the log warp maps to [-1, 1]: the geometry's
};
// The moment bias the MBOIT paper gives for a variant (docs/experiments/oit.md cites the table).
float mboit_paper_bias(MomentKind kind, int moments, int bits);

// The parameters MBOIT and STOCHASTIC add to the oit experiment, each scoped to its technique.
std::vector<ParamSpec> moment_params();

std::unique_ptr<OitCase> make_mboit_case(const ParamSet& p, CaseContext& ctx);
std::unique_ptr<OitCase> make_stochastic_case(const ParamSet& p, CaseContext& ctx);

}  // namespace oitbench::oit
