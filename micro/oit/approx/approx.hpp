#pragma once
// Approximate OIT (Brüll 2018, sections 2.3, 3.5-3.7, chapters 5 and 6): per-pixel arrays of n
// nodes filled under a per-pixel spinlock (MLAB, UMLAB, AT, HAT, UAT, UHAT), weighted blended OIT
// (McGuire & Bavoil 2013), plain unsorted blending and hybrid transparency (HT, Maule, Comba,
// Torchelsen, Bastos 2013: a k-buffer core of the n nearest fragments, the tail averaged). This header is their
// catalogue and the oit experiment's case for them (approx_case.cpp); each technique's CPU model, which a GPU image
// must match to be valid, is in approx_model.hpp; the error against the exact reference, reported
// as data, in image_compare.hpp.
#include <memory>
#include <string>
#include <vector>

#include "core/registry.hpp"
#include "oit/capture/fragment_storage.hpp"
#include "oit/oit_case.hpp"

namespace oitbench::oit {

// The technique table (techniques.hpp) names them; its entries carry the enumerator.
// GlobalSort: the splats sorted by centre depth every frame, then blended in that order (Kerbl et al. 2023).
// FirstK: HT's core alone, the rest dropped (HTGS's ALPHA_BLEND_FIRST_K, Hahlbohm et al. 2025).
// WindowSort: the global order near to far through a sorted per-pixel window (StopThePop, Radl et al. 2024).
enum class ApproxTechnique {
  Mlab,
  Umlab,
  Ht,
  At,
  Hat,
  Uat,
  Uhat,
  Laat,
  Wboit,
  Unsorted,
  GlobalSort,
  FirstK,
  WindowSort
};

// The parameters the approximate techniques add to the oit experiment (ignored by the exact ones).
std::vector<ParamSpec> approx_params();

// The oit experiment's case for an approximate technique (parameters as in micro/experiments/oit.cpp).
std::unique_ptr<OitCase> make_approx_case(const ParamSet& p, CaseContext& ctx);

}  // namespace oitbench::oit
