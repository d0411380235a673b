#pragma once
// The CPU side of exact OIT: statistics of captured lists, the reference compositor (double
// precision, the read-back fragments sorted near-to-far with a deterministic tie-break and
// composited front to back with "over") and the CPU-NATIVE resolve (native threads); the image
// comparison every resolve is validated with is in image_compare.hpp.
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "oit/capture/fragment_storage.hpp"

namespace oitbench::oit {

// What the transparent layers are composited over: the scene's constant background, or with the
// opaque effect the opaque pass's colour per pixel (row-major from the bottom row, RGB) and its
// window depth (fragments at or behind it are hidden).
struct Backdrop {
  glm::vec3 background{1.0f};
  std::vector<float> rgb;    // empty: the background everywhere
  std::vector<float> depth;  // empty: nothing hides a fragment
  Backdrop() = default;
  Backdrop(glm::vec3 bg) : background(bg) {}  // NOLINT: a constant background converts implicitly
  glm::vec3 at(size_t pixel) const {
    return rgb.empty() ? background : glm::vec3(rgb[pixel * 3], rgb[pixel * 3 + 1], rgb[pixel * 3 + 2]);
  }
  bool hides(size_t pixel, float fragment_depth) const { return !depth.empty() && !(fragment_depth < depth[pixel]); }
};

// The fragments of `lists` that the backdrop's opaque depth does not hide (the CPU's own depth
// test, for the opaque effect's reference); `hidden` counts those dropped.
HostLists visible_fragments(const HostLists& lists, const Backdrop& backdrop, size_t& hidden);
// Fragments of `lists` at or behind the backdrop's depth (0 when the capture's depth test held).
size_t hidden_fragments(const HostLists& lists, const Backdrop& backdrop);

struct ListStats {
  size_t total_fragments = 0, covered_pixels = 0;
  unsigned peak_depth = 0;
  double mean_depth = 0;        // over covered pixels
  std::vector<unsigned> depth;  // per pixel
  std::vector<bool> tied;       // per pixel: fragments of different colours at exactly the same depth
  size_t tied_pixels = 0;
  std::string error;  // a broken list (cycle, index outside the pool), else empty
};
ListStats list_stats(const HostLists& lists);
// Only each pixel's list length and the peak (what sizing a pool needs), without list_stats' sort: a
// broken list (a cycle, a node outside the pool) counts 0, as in list_stats, which names it.
struct ListDepths {
  std::vector<unsigned> depth;  // per pixel
  unsigned peak_depth = 0;
  size_t total_fragments = 0;
};
ListDepths list_depths(const HostLists& lists);

// One RGB per pixel (3 doubles), the backdrop where no fragment landed. `min_transmittance` > 0: 3DGS's early
// termination (the early_stop parameter): the fragment that would take the transmittance below it is not
// blended, nor any after it (the backdrop shows through the transmittance before it).
std::vector<double> composite_reference(const HostLists& lists, const Backdrop& backdrop, double min_transmittance = 0);

// The GPU resolves' output convention: rgb composited onto the background, alpha = how many times
// the pixel was resolved (additive blending), so uncovered pixels stay (0,0,0,0).
// CPU-NATIVE: the same resolve on `threads` native threads (0: all cores); sorts far-to-near and
// blends back to front in float, like the shaders. `perturb` changes the diagonal x == y (fault=wrong-result).
// With `min_transmittance` > 0 it composites front to back in float and stops early, as the shaders then do.
void resolve_native(const HostLists& lists, const Backdrop& backdrop, int threads, bool perturb,
                    std::vector<float>& out, float min_transmittance = 0);

// A captured fragment as the CPU models of the approximate, moment and stochastic techniques read it:
// its RGBA8 colour unpacked to floats and its depth as captured.
struct ArrivedFragment {
  glm::vec4 colour;
  float depth;
};
glm::vec4 unpack_rgba8(unsigned c);
// One pixel's fragments of RGBA8 lists in the order they arrived (the linked list prepends: its reverse).
void arrival_order(const HostLists& lists, size_t pixel, std::vector<ArrivedFragment>& out);

}  // namespace oitbench::oit
