#pragma once
// The CPU side of exact OIT: statistics of captured lists, the reference compositor (double
// precision, the read-back fragments sorted near-to-far with a deterministic tie-break and
// composited front to back with "over") and the CPU-NATIVE resolve (native threads); the image
// comparison every resolve is validated with is in image_compare.hpp.
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "oit/fragment_storage.hpp"

namespace oitbench::oit {

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

// One RGB per pixel (3 doubles), background where no fragment landed.
std::vector<double> composite_reference(const HostLists& lists, glm::vec3 background);

// The GPU resolves' output convention: rgb composited onto the background, alpha = how many times
// the pixel was resolved (additive blending), so uncovered pixels stay (0,0,0,0).
// CPU-NATIVE: the same resolve on `threads` native threads (0: all cores); sorts far-to-near and
// blends back to front in float, like the shaders. `perturb` changes the diagonal x == y (fault=wrong-result).
void resolve_native(const HostLists& lists, glm::vec3 background, int threads, bool perturb, std::vector<float>& out);

}  // namespace oitbench::oit
