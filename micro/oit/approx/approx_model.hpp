#pragma once
// The CPU model of each approximate technique (approx.hpp): the same approximation applied to the
// same fragments in the order they reached the pixel (the reversed per-pixel linked list, which on
// a rasteriser that shades each pixel's fragments in submission order is also the order the
// spinlock serialises them in). A GPU image is valid when it matches its own model.
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "oit/approx/approx.hpp"
#include "oit/capture/fragment_storage.hpp"
#include "oit/reference/reference.hpp"

namespace oitbench::oit {

struct ApproxSettings {
  ApproxTechnique technique = ApproxTechnique::Mlab;
  int nodes = 8;                   // per-pixel array techniques (LAAT stores one more: its head)
  std::string weight = "eq7";      // WBOIT: none | eq7 | eq10
  bool unguarded = false;          // the deliberately unguarded variant (hard-case tests)
  glm::vec2 near_far{0.1f, 10.f};  // the projection's planes (WBOIT eq7 works on view distance)
};

struct ApproxModel {
  std::vector<float> rgb;  // 3 floats per pixel, background where no fragment landed
};
// The technique's own CPU model on the captured fragments (see the header comment).
ApproxModel approx_model(const HostLists& lists, const Backdrop& backdrop, const ApproxSettings& s);

}  // namespace oitbench::oit
