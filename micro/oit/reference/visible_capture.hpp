#pragma once
// The view's fragments as the CPU references and models see them: the opaque pass's backdrop, then
// every transparent fragment captured (in the case's `capture` storage), read back, and less those
// the backdrop's opaque depth hides. Written once for the cases that capture their reference apart
// from the technique they time (the approximate, moment, stochastic and peeling cases).
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

#include "core/registry.hpp"
#include "oit/capture/fragment_storage.hpp"
#include "oit/reference/reference.hpp"

namespace oitbench::oit {

class ScenePasses;

struct VisibleFragments {
  Backdrop backdrop;
  HostLists host;
  size_t hidden = 0;  // fragments the backdrop's depth hid
};

// Draws the opaque pass (untimed) and captures the transparent geometry of `fx` under `view_proj`;
// the capture's memory is decided from the scene before anything is allocated (capture_budget).
VisibleFragments capture_visible_fragments(ScenePasses& fx, const glm::mat4& view_proj, const ParamSet& p,
                                           CaseContext& ctx);

// The reference side of a view: its visible fragments, the backdrop, their statistics and exact composite,
// which every CPU-model-checked case (the approximate, moment, wavelet, stochastic and slab techniques)
// compares with and builds its model from. They depend on the view, not on the technique.
struct ReferenceView {
  Backdrop backdrop;
  size_t hidden = 0;  // fragments the backdrop's depth hid
  HostLists host;
  ListStats stats;
  std::vector<double> composite;  // composite_reference(host, backdrop)
};
// Everything a ReferenceView depends on: the size, and every parameter but the technique and the technique
// parameters (Technique::params), except `capture`, the storage the fragments are captured in (so the
// scene, view, effects, fault and seed are all in it).
std::string reference_view_key(const ParamSet& p, const CaseContext& ctx);
// The view's ReferenceView: the run's cases with the same reference_view_key share one through the run's
// shared cache (only the first pays the capture, the read-back and the composite; each case still compares
// its own image with it); without a shared cache, the case's own. The
// opaque pass is drawn only when the view is made (a case draws it again in its own passes).
std::shared_ptr<const ReferenceView> reference_view(ScenePasses& fx, const glm::mat4& view_proj, const ParamSet& p,
                                                    CaseContext& ctx);

}  // namespace oitbench::oit
