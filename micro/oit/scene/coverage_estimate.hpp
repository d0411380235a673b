#pragma once
// How many fragments a draw makes, known before anything is captured: what a case's memory estimate
// (core/memory_budget.hpp) starts from, so a case too large to hold is refused in seconds instead of
// after a capture that takes minutes (a 2048x2048 view of planes-deep is 4.6 G fragments).
#include <glm/glm.hpp>

#include "core/memory_budget.hpp"
#include "oit/capture/fragment_storage.hpp"
#include "oit/scene/scene.hpp"

namespace oitbench::oit {

// The fragments of `mesh`'s transparent primitives (indices and line_indices; not opaque_indices) at
// width x height through `view_proj`, with no depth test: each triangle clipped to the view frustum
// and its area in pixels summed, each line segment's clipped length in pixels along its major axis
// (one fragment per pixel column or row it crosses). An estimate: pixels along a triangle's edges
// round either way. Each splat: the pixels of its ellipse where its alpha reaches 1/255, from its projected
// covariance (an estimate within the 3-sigma quad). One pass over the primitives.
double estimate_fragments(const Mesh& mesh, const glm::mat4& view_proj, int width, int height);

// A splat's bytes on the GPU (shaders/splats/splats.glsl: 4 vec4s; GpuSplats).
inline constexpr unsigned long long kGpuSplatBytes = 64;
// What a built scene keeps while its cases run: its splats on the CPU and on the GPU (nothing for triangles
// and lines, whose meshes are small beside their fragments).
MemoryNeed scene_held_memory(const Mesh& mesh);
// What building and uploading `splats` splats takes (scene_splat_count), before anything is built: a case
// of a scene too large for the limit is refused with it (ScenePasses).
MemoryNeed splat_scene_memory(double splats);

// make_fragment_storage's budget for a capture of `mesh` at the case's size: its estimate and the
// read-backs the case's validation holds at once (`host_copies`), beside what the scene already holds.
inline FragmentBudget capture_budget(const Mesh& mesh, const glm::mat4& view_proj, const CaseContext& ctx,
                                     int host_copies) {
  return {static_cast<unsigned long long>(estimate_fragments(mesh, view_proj, ctx.width(), ctx.height())), host_copies,
          scene_held_memory(mesh)};
}

}  // namespace oitbench::oit
