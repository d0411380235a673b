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
  bool htgs = false;               // HT: HTGS's configuration (ht_variant=htgs)
  glm::vec2 near_far{0.1f, 10.f};  // the projection's planes (WBOIT eq7 works on view distance)
  float early_stop = 0;            // GLOBAL-SORT: 3DGS's early termination threshold (0: off)
  unsigned threads = 0;            // the model's CPU threads (0: every core); its result does not depend on it
};

struct ApproxModel {
  std::vector<float> rgb;  // 3 floats per pixel, background where no fragment landed
  std::string error;       // why the model could not be built where it could not, else empty
};
// The technique's own CPU model on the captured fragments (see the header comment); pixels are
// independent, so their rows are spread over the cores (core/parallel_rows.hpp).
ApproxModel approx_model(const HostLists& lists, const Backdrop& backdrop, const ApproxSettings& s);

// WINDOW-SORT's model (shaders/approx/insert/window.glsl): each pixel's fragments in the global order
// (stably sorted by the depth keys of `order`, captured with splat_depth=centre: their splats' centres,
// near to far), each with its depth key from `keys` (the same fragments in the same arrival order, captured
// with the case's own splat_depth), through a sorted window of `window` fragments whose nearest is blended
// front to back whenever it overflows, then the window flushed in order. A pixel whose two captures hold
// different fragment counts is an error of the model (the first such pixel in pixel order). `threads`: as
// ApproxSettings::threads.
ApproxModel window_sort_model(const HostLists& order, const HostLists& keys, const Backdrop& backdrop, int window,
                              unsigned threads = 0);
// packUnorm4x8 on the CPU: a fragment's colour as the k-buffer nodes hold it.
unsigned pack_rgba8(glm::vec4 v);

}  // namespace oitbench::oit
