#include "oit/reference/reference.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <limits>
#include <thread>

#include "core/parallel_rows.hpp"

namespace oitbench::oit {

namespace {

struct Frag {
  float depth;
  std::array<unsigned, 4> colour;  // the tie key: equal depths are ordered by it (node_tie_key)
  glm::dvec4 rgba;                 // the stored colour, decoded
};

// Collects one pixel's fragments in list order; false if the list is broken.
bool gather(const HostLists& l, size_t pixel, std::vector<Frag>& out) {
  out.clear();
  for (unsigned n = l.heads[pixel]; n != kListEnd; n = l.next[n]) {
    if (n >= l.nodes.size() || out.size() > l.nodes.size()) return false;
    out.push_back({std::bit_cast<float>(l.nodes[n].y), node_tie_key(l, n), node_colour(l, n)});
  }
  return true;
}

// The rows of the lists' image and the threads that spread them over the cores (validation runs outside
// the timed regions, so it may take them all: core/parallel_rows.hpp).
size_t row_of(const HostLists& l) { return static_cast<size_t>(std::max(1, l.width)); }
unsigned reference_threads(const HostLists& l) {
  return parallel_row_threads((l.heads.size() + row_of(l) - 1) / row_of(l));
}

}  // namespace

ListStats list_stats(const HostLists& l) {
  ListStats s;
  size_t pixels = l.heads.size();
  s.depth.resize(pixels);
  std::vector<char> tied(pixels, 0);
  struct Partial {
    size_t total = 0, covered = 0, first_broken = std::numeric_limits<size_t>::max();
    unsigned peak = 0;
    std::vector<Frag> f;
  };
  const unsigned threads = reference_threads(l);
  std::vector<Partial> part(threads);
  parallel_rows(l.heads.size(), row_of(l), threads, [&](unsigned t, size_t p) {
    Partial& w = part[t];
    if (!gather(l, p, w.f)) {
      w.first_broken = std::min(w.first_broken, p);
      return;
    }
    s.depth[p] = static_cast<unsigned>(w.f.size());
    std::sort(w.f.begin(), w.f.end(), [](const Frag& a, const Frag& b) { return a.depth < b.depth; });
    for (size_t i = 1; i < w.f.size(); ++i)
      if (w.f[i].depth == w.f[i - 1].depth && w.f[i].colour != w.f[i - 1].colour) {
        tied[p] = 1;
        break;
      }
    w.total += w.f.size();
    w.peak = std::max(w.peak, s.depth[p]);
    if (!w.f.empty()) ++w.covered;
  });
  size_t broken = std::numeric_limits<size_t>::max();
  for (const auto& w : part) {
    s.total_fragments += w.total;
    s.covered_pixels += w.covered;
    s.peak_depth = std::max(s.peak_depth, w.peak);
    broken = std::min(broken, w.first_broken);
  }
  if (broken < pixels)
    s.error = "the list of pixel (" + std::to_string(broken % l.width) + "," + std::to_string(broken / l.width) +
              ") is broken (a cycle or a node outside the pool)";
  s.tied.assign(pixels, false);
  for (size_t p = 0; p < pixels; ++p)
    if (tied[p]) {
      s.tied[p] = true;
      ++s.tied_pixels;
    }
  s.mean_depth = s.covered_pixels ? static_cast<double>(s.total_fragments) / s.covered_pixels : 0.0;
  return s;
}

ListDepths list_depths(const HostLists& l) {
  ListDepths d;
  d.depth.assign(l.heads.size(), 0);
  for (size_t p = 0; p < l.heads.size(); ++p) {
    size_t n = 0;
    unsigned i = l.heads[p];
    for (; i != kListEnd && i < l.nodes.size() && n <= l.nodes.size(); i = l.next[i]) ++n;
    if (i != kListEnd) continue;  // broken: counted as list_stats counts it (0)
    d.depth[p] = static_cast<unsigned>(n);
    d.peak_depth = std::max(d.peak_depth, d.depth[p]);
    d.total_fragments += n;
  }
  return d;
}

HostLists visible_fragments(const HostLists& l, const Backdrop& b, size_t& hidden) {
  HostLists out;
  out.width = l.width;
  out.height = l.height;
  out.colour = l.colour;
  out.error = l.error;
  out.heads.assign(l.heads.size(), kListEnd);
  hidden = 0;
  std::vector<unsigned> kept;
  for (size_t p = 0; p < l.heads.size(); ++p) {
    kept.clear();
    for (unsigned n = l.heads[p]; n != kListEnd && n < l.nodes.size() && kept.size() <= l.nodes.size(); n = l.next[n])
      kept.push_back(n);
    // Relinked in list order (head first): a pixel's order is the capture's, minus the hidden ones.
    for (auto it = kept.rbegin(); it != kept.rend(); ++it) {
      if (b.hides(p, std::bit_cast<float>(l.nodes[*it].y))) {
        ++hidden;
        continue;
      }
      out.nodes.push_back(l.nodes[*it]);
      if (!l.wide.empty()) out.wide.push_back(l.wide[*it]);
      out.next.push_back(out.heads[p]);
      out.heads[p] = static_cast<unsigned>(out.nodes.size() - 1);
    }
  }
  if (!l.counts.empty()) {
    out.counts.assign(l.heads.size(), 0);
    for (size_t p = 0; p < l.heads.size(); ++p)
      for (unsigned n = out.heads[p]; n != kListEnd; n = out.next[n]) ++out.counts[p];
  }
  return out;
}

size_t hidden_fragments(const HostLists& l, const Backdrop& b) {
  size_t hidden = 0;
  if (b.depth.empty()) return 0;
  std::vector<Frag> f;
  for (size_t p = 0; p < l.heads.size(); ++p) {
    gather(l, p, f);
    for (const auto& fr : f) hidden += b.hides(p, fr.depth);
  }
  return hidden;
}

std::vector<double> composite_reference(const HostLists& l, const Backdrop& backdrop, double min_transmittance) {
  size_t pixels = l.heads.size();
  std::vector<double> out(pixels * 3);
  const unsigned threads = reference_threads(l);
  std::vector<std::vector<Frag>> frags(threads);
  parallel_rows(l.heads.size(), row_of(l), threads, [&](unsigned t, size_t p) {
    std::vector<Frag>& f = frags[t];
    gather(l, p, f);
    // Near to far; equal depths ordered by colour bits so the reference never depends on list order.
    std::stable_sort(f.begin(), f.end(), [](const Frag& a, const Frag& b) {
      return a.depth != b.depth ? a.depth < b.depth : a.colour < b.colour;
    });
    glm::dvec3 c(0.0);
    double transmittance = 1.0;
    for (const auto& fr : f) {
      const glm::dvec4& k = fr.rgba;
      const double next = transmittance * (1.0 - k.a);
      if (next < min_transmittance) break;  // early termination (never with 0)
      c += transmittance * k.a * glm::dvec3(k);
      transmittance = next;
    }
    c += transmittance * glm::dvec3(backdrop.at(p));
    for (int k = 0; k < 3; ++k) out[p * 3 + k] = c[k];
  });
  return out;
}

namespace {

// Far-to-near fragments composited front to back (the last first) in float over `backdrop`, stopping at
// the fragment that would take the transmittance below `min_transmittance` (the shaders' EARLY_STOP).
glm::vec3 composite_front_to_back(const std::vector<Frag>& f, glm::vec3 backdrop, float min_transmittance) {
  glm::vec3 c(0.0f);
  float t = 1.0f;
  for (auto it = f.rbegin(); it != f.rend(); ++it) {
    const glm::vec4 k(it->rgba);
    const float next = t * (1.0f - k.a);
    if (next < min_transmittance) break;
    c += t * k.a * glm::vec3(k);
    t = next;
  }
  return c + t * backdrop;
}

}  // namespace

void resolve_native(const HostLists& l, const Backdrop& backdrop, int threads, bool perturb, std::vector<float>& out,
                    float min_transmittance) {
  size_t pixels = l.heads.size();
  out.assign(pixels * 4, 0.0f);
  if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  auto work = [&](int t) {
    std::vector<Frag> f;
    for (size_t row = t; row < static_cast<size_t>(l.height); row += threads)
      for (size_t p = row * l.width; p < (row + 1) * l.width; ++p) {
        if (l.heads[p] == kListEnd) continue;
        gather(l, p, f);
        std::sort(f.begin(), f.end(), [](const Frag& a, const Frag& b) {
          return a.depth != b.depth ? a.depth > b.depth : a.colour > b.colour;  // the reference's tie-break
        });
        glm::vec3 c = backdrop.at(p);
        if (min_transmittance > 0)
          c = composite_front_to_back(f, c, min_transmittance);
        else
          for (const auto& fr : f) {
            glm::vec4 k(fr.rgba);
            // "over" with one rounding per channel (fma), as GPUs blend: 5000 layers of alpha 1e-4 in
            // rgba32f stay within 1e-6 of the truth, where a separately rounded mix drifts by 6e-5.
            for (int ch = 0; ch < 3; ++ch) c[ch] = std::fma(k.a, k[ch] - c[ch], c[ch]);
          }
        if (perturb && p % l.width == row) c.r += 1.0f / 64.0f;  // the diagonal, like the shaders
        out[p * 4 + 0] = c.r;
        out[p * 4 + 1] = c.g;
        out[p * 4 + 2] = c.b;
        out[p * 4 + 3] = 1.0f;
      }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work, t);
  work(0);
  for (auto& th : pool) th.join();
}

glm::vec4 unpack_rgba8(unsigned c) {
  auto unorm8 = [c](int k) { return static_cast<float>((c >> (8 * k)) & 0xffu) / 255.0f; };
  return {unorm8(0), unorm8(1), unorm8(2), unorm8(3)};
}

void arrival_order(const HostLists& lists, size_t pixel, std::vector<ArrivedFragment>& out) {
  out.clear();
  for (unsigned i = lists.heads[pixel]; i != kListEnd && i < lists.nodes.size() && out.size() <= lists.nodes.size();
       i = lists.next[i])
    out.push_back({unpack_rgba8(lists.nodes[i].x), std::bit_cast<float>(lists.nodes[i].y)});
  std::reverse(out.begin(), out.end());
}

}  // namespace oitbench::oit
