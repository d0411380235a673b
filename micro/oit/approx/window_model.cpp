// WINDOW-SORT's CPU model (approx_model.hpp): the windowed sort of shaders/approx/insert/window.glsl on
// the captured fragments, replayed in the global order the GPU draws the splats in.
#include <algorithm>
#include <numeric>

#include "oit/approx/approx_model.hpp"

namespace oitbench::oit {

namespace {

struct Pending {
  float depth;
  unsigned colour;  // packUnorm4x8, as the window's nodes hold it
};
// insert/kbuffer.glsl's order: depth, then the packed colour.
bool precedes(const Pending& a, const Pending& b) {
  return a.depth < b.depth || (a.depth == b.depth && a.colour < b.colour);
}

// Front to back: C += T a c, T *= 1 - a (window.glsl's window_blend).
struct FrontToBack {
  glm::vec3 c{0.0f};
  float t = 1.0f;
  void blend(unsigned colour) {
    glm::vec4 k = unpack_rgba8(colour);
    c += t * k.a * glm::vec3(k);
    t *= 1.0f - k.a;
  }
};

// One pixel: `order` gives the global order's keys, `keys` the fragments' own keys and colours.
glm::vec3 window_pixel(const std::vector<ArrivedFragment>& order, const std::vector<ArrivedFragment>& keys,
                       size_t window, glm::vec3 bg, std::vector<size_t>& index, std::vector<Pending>& pending) {
  index.resize(order.size());
  std::iota(index.begin(), index.end(), size_t{0});
  // the radix sort is stable: equal centre depths keep their submission (arrival) order
  std::stable_sort(index.begin(), index.end(), [&](size_t a, size_t b) { return order[a].depth < order[b].depth; });
  pending.clear();
  FrontToBack out;
  for (size_t i : index) {
    const Pending f{keys[i].depth, pack_rgba8(keys[i].colour)};
    pending.insert(std::upper_bound(pending.begin(), pending.end(), f, precedes), f);
    if (pending.size() > window) {  // full: the nearest of the window and the new fragment leaves
      out.blend(pending.front().colour);
      pending.erase(pending.begin());
    }
  }
  for (const Pending& f : pending) out.blend(f.colour);  // the resolve flushes the window in order
  return out.c + out.t * bg;
}

}  // namespace

ApproxModel window_sort_model(const HostLists& order, const HostLists& keys, const Backdrop& backdrop, int window) {
  const size_t pixels = keys.heads.size();
  ApproxModel m;
  m.rgb.resize(pixels * 3);
  if (order.heads.size() != pixels) {
    m.error = "the global order's capture has " + std::to_string(order.heads.size()) + " pixels, the keys' " +
              std::to_string(pixels);
    return m;
  }
  std::vector<ArrivedFragment> by_order, by_key;
  std::vector<size_t> index;
  std::vector<Pending> pending;
  for (size_t p = 0; p < pixels; ++p) {
    arrival_order(order, p, by_order);
    arrival_order(keys, p, by_key);
    glm::vec3 c = backdrop.at(p);
    if (by_order.size() != by_key.size()) {
      if (m.error.empty())
        m.error = "pixel " + std::to_string(p) + ": " + std::to_string(by_order.size()) +
                  " fragments captured with the centre key, " + std::to_string(by_key.size()) + " with the case's key";
    } else {
      c = window_pixel(by_order, by_key, static_cast<size_t>(window), c, index, pending);
    }
    for (int k = 0; k < 3; ++k) m.rgb[p * 3 + k] = c[k];
  }
  return m;
}

}  // namespace oitbench::oit
