#pragma once
// The view's fragments as the CPU references and models see them: the opaque pass's backdrop, then
// every transparent fragment captured (in the case's `capture` storage), read back, and less those
// the backdrop's opaque depth hides. Written once for the cases that capture their reference apart
// from the technique they time (the approximate, moment, stochastic and peeling cases).
#include <glm/glm.hpp>

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

}  // namespace oitbench::oit
