// WINDOW-SORT's CPU model (approx_model.hpp): the windowed sort of shaders/approx/insert/window.glsl on
// the captured fragments, replayed in the global order the GPU draws the splats in.
#include <algorithm>
#include <limits>
#include <numeric>

#include "core/parallel_rows.hpp"
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

ApproxModel window_sort_model(const HostLists& order, const HostLists& keys, const Backdrop& backdrop, int window,
                              unsigned threads) {
  const size_t pixels = keys.heads.size();
  ApproxModel m;
  m.rgb.resize(pixels * 3);
  if (order.heads.size() != pixels) {
    m.error = "the global order's capture has " + std::to_string(order.heads.size()) + " pixels, the keys' " +
              std::to_string(pixels);
    return m;
  }
  const size_t row = static_cast<size_t>(std::max(1, keys.width));
  // Each thread's scratch, and the first pixel (in pixel order, whichever thread met it) whose captures differ.
  struct Scratch {
    std::vector<ArrivedFragment> by_order, by_key;
    std::vector<size_t> index;
    std::vector<Pending> pending;
    size_t first_error = std::numeric_limits<size_t>::max();
    std::string error;
  };
  std::vector<Scratch> scratch(parallel_row_threads((pixels + row - 1) / row, threads));
  parallel_rows(pixels, row, threads, [&](unsigned thread, size_t p) {
    Scratch& sc = scratch[thread];
    arrival_order(order, p, sc.by_order);
    arrival_order(keys, p, sc.by_key);
    glm::vec3 c = backdrop.at(p);
    if (sc.by_order.size() != sc.by_key.size()) {
      if (p < sc.first_error) {
        sc.first_error = p;
        sc.error = "pixel " + std::to_string(p) + ": " + std::to_string(sc.by_order.size()) +
                   " fragments captured with the centre key, " + std::to_string(sc.by_key.size()) +
                   " with the case's key";
      }
    } else {
      c = window_pixel(sc.by_order, sc.by_key, static_cast<size_t>(window), c, sc.index, sc.pending);
    }
    for (int k = 0; k < 3; ++k) m.rgb[p * 3 + k] = c[k];
  });
  size_t first = std::numeric_limits<size_t>::max();
  for (const Scratch& sc : scratch)
    if (sc.first_error < first) {
      first = sc.first_error;
      m.error = sc.error;
    }
  return m;
}

}  // namespace oitbench::oit
