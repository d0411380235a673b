#pragma once
// How many fragments a draw makes, known before anything is captured: what a case's memory estimate
// (core/memory_budget.hpp) starts from, so a case too large to hold is refused in seconds instead of
// after a capture that takes minutes (a 2048x2048 view of planes-deep is 4.6 G fragments).
#include <glm/glm.hpp>

#include "oit/capture/fragment_storage.hpp"
#include "oit/scene/scene.hpp"

namespace oitbench::oit {

// The fragments of `mesh`'s transparent primitives (indices and line_indices; not opaque_indices) at
// width x height through `view_proj`, with no depth test: each triangle clipped to the view frustum
// and its area in pixels summed, each line segment's clipped length in pixels along its major axis
// (one fragment per pixel column or row it crosses). An estimate: pixels along a triangle's edges
// round either way. One pass over the primitives.
double estimate_fragments(const Mesh& mesh, const glm::mat4& view_proj, int width, int height);

// make_fragment_storage's budget for a capture of `mesh` at the case's size: its estimate and the
// read-backs the case's validation holds at once (`host_copies`).
inline FragmentBudget capture_budget(const Mesh& mesh, const glm::mat4& view_proj, const CaseContext& ctx,
                                     int host_copies) {
  return {static_cast<unsigned long long>(estimate_fragments(mesh, view_proj, ctx.width(), ctx.height())), host_copies};
}

}  // namespace oitbench::oit
