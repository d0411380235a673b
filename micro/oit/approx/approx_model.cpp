#include "oit/approx/approx_model.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "core/parallel_rows.hpp"

namespace oitbench::oit {

namespace {

constexpr float kDepthEmpty = std::numeric_limits<float>::max();
constexpr unsigned kOneBits = 0x3F800000u;

// --- The node encodings of shaders/approx/nodes.glsl, on the CPU --------------------------------
using Node = glm::uvec2;

unsigned pack_unorm(float v) { return static_cast<unsigned>(std::nearbyint(std::clamp(v, 0.0f, 1.0f) * 255.0f)); }
unsigned pack4(glm::vec4 v) { return pack_rgba8(v); }

float node_depth(Node n) { return n.y == 0u ? kDepthEmpty : std::bit_cast<float>(n.y - 1u); }
unsigned encode_depth(float z) { return z >= kDepthEmpty ? 0u : std::bit_cast<unsigned>(z) + 1u; }
glm::vec4 mlab_value(Node n) {
  glm::vec4 k = unpack_rgba8(n.x);
  return {k.x, k.y, k.z, 1.0f - k.w};
}
Node mlab_node(glm::vec4 ct, float z) { return {pack4({ct.x, ct.y, ct.z, 1.0f - ct.w}), encode_depth(z)}; }
float at_transmittance(Node n) { return std::bit_cast<float>(n.x ^ kOneBits); }
float laat_transmittance(Node n) { return std::bit_cast<float>((n.x & ~31u) ^ kOneBits); }
Node laat_node(float t, float z, int next) {
  return {((std::bit_cast<unsigned>(t) ^ kOneBits) & ~31u) | static_cast<unsigned>(next + 1), encode_depth(z)};
}
Node at_node(float t, float z) { return {std::bit_cast<unsigned>(t) ^ kOneBits, encode_depth(z)}; }

glm::vec4 merge(glm::vec4 a, glm::vec4 b) { return {glm::vec3(a) + a.w * glm::vec3(b), a.w * b.w}; }

// --- The insertions of shaders/approx/insert/ (one file per technique), on the CPU ---------
void insert_mlab(std::vector<Node>& s, int n, glm::vec4 ct, float z) {
  std::vector<glm::vec4> c(n + 1);
  std::vector<float> d(n + 1);
  c[0] = ct;
  d[0] = z;
  for (int i = 0; i < n; ++i) {
    c[i + 1] = mlab_value(s[i]);
    d[i + 1] = node_depth(s[i]);
  }
  for (int i = 0; i < n; ++i)
    if (d[i] > d[i + 1]) {
      std::swap(c[i], c[i + 1]);
      std::swap(d[i], d[i + 1]);
    }
  c[n - 1] = merge(c[n - 1], c[n]);
  for (int i = 0; i < n; ++i) s[i] = mlab_node(c[i], d[i]);
}

void insert_umlab(std::vector<Node>& s, int n, glm::vec4 ct, float z) {
  std::vector<glm::vec4> c(n + 1);
  std::vector<float> d(n + 1);
  c[n] = ct;
  d[n] = z;
  for (int i = 0; i < n; ++i) {
    c[i] = mlab_value(s[i]);
    d[i] = node_depth(s[i]);
  }
  int max_idx = 0;
  float max_z = -1.0f;
  for (int i = 0; i <= n; ++i)
    if (d[i] > max_z) max_z = d[i], max_idx = i;
  if (max_z == kDepthEmpty) {
    s[max_idx] = mlab_node(ct, z);
    return;
  }
  int smax_idx = 0;
  float smax_z = -1.0f;
  for (int i = 0; i <= n; ++i)
    if (d[i] > smax_z && i != max_idx) smax_z = d[i], smax_idx = i;
  glm::vec4 merged = merge(c[smax_idx], c[max_idx]);
  if (max_idx == n) {
    max_idx = smax_idx;
    smax_idx = n;
  }
  s[max_idx] = mlab_node(merged, smax_z);
  if (smax_idx != n) s[smax_idx] = mlab_node(ct, z);
}

void insert_at(std::vector<Node>& s, int n, float a, float z, bool height, bool unguarded) {
  std::vector<float> t(n + 1), d(n + 1);
  int k = 0;
  for (int i = 0; i < n; ++i) {
    t[i] = at_transmittance(s[i]);
    d[i] = node_depth(s[i]);
    if (d[i] <= z) k = i + 1;
  }
  for (int i = n; i > k; --i) {
    t[i] = t[i - 1] * a;
    d[i] = d[i - 1];
  }
  t[k] = (k > 0 ? t[k - 1] : 1.0f) * a;
  d[k] = z;
  if (d[n] != kDepthEmpty) {
    int r = 1;
    float best = kDepthEmpty;
    for (int i = 1; i <= n; ++i) {
      float h = t[i - 1] - t[i];
      float e = height ? h * h / (unguarded ? t[i - 1] : std::max(t[i - 1], 1e-30f)) : (d[i] - d[i - 1]) * h;
      if (e < best) best = e, r = i;
    }
    t[r - 1] = t[r];
    for (int i = r; i < n; ++i) {
      t[i] = t[i + 1];
      d[i] = d[i + 1];
    }
  }
  for (int i = 0; i < n; ++i) s[i] = at_node(t[i], d[i]);
}

// UAT's and LAAT's rect metric over the nodes in depth order `seq[0..n]` (relative transmittances t,
// depths d): the position r >= 1 whose merge into r - 1 loses the least area under the visibility curve.
int least_rect_area(const std::vector<int>& seq, int n, const std::vector<float>& t, const std::vector<float>& d) {
  float before = t[seq[0]];
  int r = 1;
  float best = kDepthEmpty;
  for (int i = 1; i <= n; ++i) {
    float after = before * t[seq[i]];
    float e = (d[seq[i]] - d[seq[i - 1]]) * (before - after);
    if (e < best) best = e, r = i;
    before = after;
  }
  return r;
}

// The unbounded AT variants' last step (slot n is the new fragment (a, z), t its node's relative
// transmittance, d its depth): node `remove` merges into node `compress`, and the new fragment takes
// the freed slot unless it was the one removed.
void merge_into(std::vector<Node>& s, int n, int compress, int remove, const std::vector<float>& t,
                const std::vector<float>& d, float a, float z) {
  float tc = t[compress] * t[remove];
  if (compress == n) {
    s[remove] = at_node(tc, d[n]);
  } else {
    s[compress] = at_node(tc, d[compress]);
    if (remove != n) s[remove] = at_node(a, z);
  }
}

void insert_uat(std::vector<Node>& s, int n, float a, float z) {
  std::vector<float> t(n + 1), d(n + 1);
  t[n] = a;
  d[n] = z;
  int empty = -1;
  for (int i = 0; i < n; ++i) {
    t[i] = at_transmittance(s[i]);
    d[i] = node_depth(s[i]);
    if (empty < 0 && d[i] == kDepthEmpty) empty = i;
  }
  if (empty >= 0) {
    s[empty] = at_node(a, z);
    return;
  }
  std::vector<int> order(n + 1);
  for (int i = 0; i <= n; ++i) order[i] = i;
  for (int i = 1; i <= n; ++i)
    for (int j = i; j > 0; --j) {
      int x = order[j - 1], y = order[j];
      if (d[x] > d[y] || (d[x] == d[y] && x > y)) order[j - 1] = y, order[j] = x;
    }
  int r = least_rect_area(order, n, t, d);
  int remove = order[r], compress = order[r - 1];
  merge_into(s, n, compress, remove, t, d, a, z);
}

void insert_uhat(std::vector<Node>& s, int n, float a, float z, bool unguarded) {
  std::vector<float> t(n + 1), d(n + 1);
  float max_depth = z, min_depth = z, product = a, last = a;
  int max_index = n, min_index = n;
  t[n] = a;
  d[n] = z;
  for (int i = 0; i < n; ++i) {
    t[i] = at_transmittance(s[i]);
    d[i] = node_depth(s[i]);
    product *= t[i];
    if (d[i] > max_depth) max_depth = d[i], last = t[i], max_index = i;
    if (d[i] < min_depth) min_depth = d[i], min_index = i;
  }
  if (max_depth == kDepthEmpty) {
    s[max_index] = at_node(a, z);
    return;
  }
  const float e = 0.00000001f;
  auto guard = [&](float x) { return unguarded ? x : std::max(x, e); };
  float exponent = std::log(guard(product / guard(last))) / guard(max_depth - min_depth), offset = -min_depth;
  float min_height = kDepthEmpty;
  int remove = min_index == 0 ? 1 : 0;
  for (int i = 0; i <= n; ++i) {
    float h = std::exp(exponent * (d[i] + offset)) * (1.0f - t[i]) * (1.0f - t[i]);
    if (h < min_height && i != min_index) min_height = h, remove = i;
  }
  int compress = min_index;
  for (int i = 0; i <= n; ++i)
    if (i != remove && d[i] <= d[remove] && d[i] > d[compress]) compress = i;
  merge_into(s, n, compress, remove, t, d, a, z);
}

// LAAT (section 6.2): s holds n node slots and the head slot (index n).
void insert_laat(std::vector<Node>& s, int n, float a, float z) {
  std::vector<float> t(n + 1), d(n + 1);
  std::vector<int> seq(n + 1);
  unsigned head = s[n].x;
  int cnt = 0, k = 0, slot = static_cast<int>(head) - 1;
  for (int i = 0; i < n && slot >= 0; ++i) {
    t[slot] = laat_transmittance(s[slot]);
    d[slot] = node_depth(s[slot]);
    if (d[slot] <= z) k = cnt + 1;
    seq[cnt++] = slot;
    slot = static_cast<int>(s[slot].x & 31u) - 1;
  }
  t[n] = a;
  d[n] = z;
  for (int i = cnt; i > k; --i) seq[i] = seq[i - 1];
  seq[k] = n;
  int len = cnt + 1, new_slot = cnt;
  if (cnt == n) {
    int r = least_rect_area(seq, n, t, d);
    t[seq[r - 1]] *= t[seq[r]];
    new_slot = seq[r];
    for (int i = r; i < n; ++i) seq[i] = seq[i + 1];
    len = n;
  }
  std::vector<Node> out = s;
  for (int i = 0; i < len; ++i) {
    int x = seq[i];
    int next = i + 1 < len ? (seq[i + 1] == n ? new_slot : seq[i + 1]) : -1;
    out[x == n ? new_slot : x] = laat_node(t[x], d[x], next);
  }
  out[n] = Node(static_cast<unsigned>((seq[0] == n ? new_slot : seq[0]) + 1), 0u);
  s = out;
}

float visibility(const std::vector<Node>& s, float z, bool relative, bool laat) {
  float v = 1.0f;
  for (const Node& node : s) {
    float t = laat ? laat_transmittance(node) : at_transmittance(node);
    if (node_depth(node) < z) v = relative ? v * t : t;
  }
  return v;
}

float wboit_weight(const std::string& w, float d, glm::vec2 nf) {
  if (w == "none") return 1.0f;
  if (w == "eq7") {
    float z = nf.x * nf.y / (nf.y - d * (nf.y - nf.x));
    return std::clamp(10.0f / (1e-5f + std::pow(z / 5.0f, 2.0f) + std::pow(z / 200.0f, 6.0f)), 1e-2f, 3e3f);
  }
  return std::clamp(3e3f * std::pow(1.0f - d, 3.0f), 1e-2f, 3e3f);
}

// HTGS's core admission (shaders/approx/nodes.glsl's HTGS_CORE_ALPHA).
constexpr float kHtgsCoreAlpha = 0.05f;

// HT on the CPU: the core of the n nearest fragments in `s`, then the tail averaged behind it; without
// `tail_on` (FIRST-K) the core alone over the background. `htgs`: HTGS's configuration (only fragments of
// alpha 0.05 or more enter the core; the tail covers 1 - prod (1 - a)).
glm::vec3 ht_pixel(const std::vector<ArrivedFragment>& frags, std::vector<Node>& s, int n, glm::vec3 bg, bool tail_on,
                   bool htgs) {
  // The core: the n nearest fragments in (depth, colour) order, as shaders/approx/insert/ht.glsl.
  std::fill(s.begin(), s.end(), Node(0u));
  for (const auto& f : frags) {
    unsigned key = pack4(f.colour);
    float z = f.depth;
    if (htgs && f.colour.w < kHtgsCoreAlpha) continue;
    for (int i = 0; i < n; ++i) {
      float nz = node_depth(s[i]);
      if (z < nz || (z == nz && key < s[i].x)) {
        Node old = s[i];
        s[i] = {key, encode_depth(z)};
        if (nz == kDepthEmpty) break;
        key = old.x;
        z = nz;
      }
    }
  }
  glm::vec3 acc(0.0f);
  float t = 1.0f;
  for (const Node& node : s) {
    glm::vec4 k = unpack_rgba8(node.x);
    acc += t * k.w * glm::vec3(k);
    t *= 1.0f - k.w;
  }
  if (!tail_on) return acc + t * bg;
  // The tail (ht_tail.frag): every fragment behind a full core's last node, averaged.
  const Node last = s[n - 1];
  const float last_z = node_depth(last);
  glm::vec4 sum(0.0f);
  float count = 0.0f, product = 1.0f;
  for (const auto& f : frags) {
    unsigned key = pack4(f.colour);
    if ((last_z != kDepthEmpty && (f.depth > last_z || (f.depth == last_z && key > last.x))) ||
        (htgs && f.colour.w < kHtgsCoreAlpha)) {
      sum += glm::vec4(glm::vec3(f.colour) * f.colour.w, f.colour.w);
      count += 1.0f;
      product *= 1.0f - f.colour.w;
    }
  }
  glm::vec3 tail(0.0f);
  float tail_t = 1.0f;
  if (htgs) {
    tail_t = product;
    if (sum.w > 0.0f) tail = glm::vec3(sum) / sum.w * (1.0f - tail_t);
  } else if (count > 0.0f) {
    tail_t = std::pow(std::clamp(1.0f - sum.w / count, 0.0f, 1.0f), count);
    if (sum.w > 0.0f) tail = glm::vec3(sum) / sum.w * (1.0f - tail_t);
  }
  return acc + t * (tail + tail_t * bg);
}

// WBOIT on the CPU: the weighted average of the colours over the product of the revealages.
glm::vec3 wboit_pixel(const std::vector<ArrivedFragment>& frags, const ApproxSettings& st, glm::vec3 bg) {
  glm::vec4 acc(0.0f);
  float reveal = 1.0f;
  for (const auto& f : frags) {
    float w = f.colour.a * wboit_weight(st.weight, f.depth, st.near_far);
    acc += glm::vec4(glm::vec3(f.colour) * w, w);
    reveal *= 1.0f - f.colour.a;
  }
  if (frags.empty()) return bg;
  glm::vec3 average = glm::vec3(acc) / (st.unguarded ? acc.a : std::clamp(acc.a, 1e-4f, 5e4f));
  return average * (1.0f - reveal) + bg * reveal;
}

// One fragment (premultiplied colour, transmittance in w) into the nodes of MLAB, UMLAB or the AT family.
void insert_node(ApproxTechnique tech, std::vector<Node>& s, int n, glm::vec4 ct, float depth, bool unguarded) {
  using T = ApproxTechnique;
  switch (tech) {
    case T::Mlab:
      insert_mlab(s, n, ct, depth);
      break;
    case T::Umlab:
      insert_umlab(s, n, ct, depth);
      break;
    case T::At:
      insert_at(s, n, ct.w, depth, false, unguarded);
      break;
    case T::Hat:
      insert_at(s, n, ct.w, depth, true, unguarded);
      break;
    case T::Uat:
      insert_uat(s, n, ct.w, depth);
      break;
    case T::Laat:
      insert_laat(s, n, ct.w, depth);
      break;
    default:
      insert_uhat(s, n, ct.w, depth, unguarded);
      break;
  }
}

// MLAB and UMLAB's resolve: the nodes composited near to far (UMLAB's insertion sort is stable).
glm::vec3 mlab_pixel(const std::vector<Node>& s, bool unsorted_nodes, glm::vec3 bg) {
  std::vector<std::pair<float, glm::vec4>> nodes;
  for (const Node& node : s) nodes.push_back({node_depth(node), mlab_value(node)});
  if (unsorted_nodes)
    std::stable_sort(nodes.begin(), nodes.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  glm::vec3 acc(0.0f);
  float t = 1.0f;
  for (const auto& [z, ct] : nodes) {
    acc += t * glm::vec3(ct);
    t *= ct.w;
  }
  return acc + t * bg;
}

// The AT family's resolve: each fragment weighted by the visibility the nodes hold at its depth.
glm::vec3 at_pixel(const std::vector<ArrivedFragment>& frags, const std::vector<Node>& s, bool relative, bool laat,
                   bool unguarded, glm::vec3 bg) {
  glm::vec4 acc(0.0f);
  for (const auto& f : frags) {
    float w = f.colour.a * visibility(s, f.depth, relative, laat);
    acc += glm::vec4(glm::vec3(f.colour) * w, w);
  }
  float total = visibility(s, kDepthEmpty, relative, laat), opacity = 1.0f - total;
  if (!unguarded && acc.a > opacity * (1.0f + 1e-5f) + 1e-6f)
    acc = glm::vec4(glm::vec3(acc) * (opacity / acc.a), acc.a);
  return glm::vec3(acc) + total * bg;
}

// GLOBAL-SORT: far to near with "over"; with early_stop near to far (ties in arrival order both ways, as the
// stable radix sort keeps them), front to back, stopping at the fragment that would take T below it.
glm::vec3 global_sort_pixel(std::vector<ArrivedFragment>& frags, float early_stop, glm::vec3 bg) {
  if (early_stop <= 0) {
    std::stable_sort(frags.begin(), frags.end(),
                     [](const ArrivedFragment& a, const ArrivedFragment& b) { return a.depth > b.depth; });
    for (const auto& f : frags) bg = glm::vec3(f.colour) * f.colour.a + bg * (1.0f - f.colour.a);
    return bg;
  }
  std::stable_sort(frags.begin(), frags.end(),
                   [](const ArrivedFragment& a, const ArrivedFragment& b) { return a.depth < b.depth; });
  glm::vec3 c(0.0f);
  float t = 1.0f;
  for (const auto& f : frags) {
    const float next = t * (1.0f - f.colour.a);
    if (next < early_stop) break;
    c += t * f.colour.a * glm::vec3(f.colour);
    t = next;
  }
  return c + t * bg;
}

}  // namespace

unsigned pack_rgba8(glm::vec4 v) {
  return pack_unorm(v.x) | pack_unorm(v.y) << 8 | pack_unorm(v.z) << 16 | pack_unorm(v.w) << 24;
}

ApproxModel approx_model(const HostLists& l, const Backdrop& backdrop, const ApproxSettings& st) {
  const size_t pixels = l.heads.size();
  const int n = st.nodes;
  ApproxModel m;
  m.rgb.resize(pixels * 3);
  using T = ApproxTechnique;
  const T tech = st.technique;
  const bool laat = tech == T::Laat, relative = tech == T::Uat || tech == T::Uhat || laat;
  const size_t row = static_cast<size_t>(std::max(1, l.width));
  // Each thread's scratch: the pixel's fragments and its node array (LAAT's has one more: its head).
  struct Scratch {
    std::vector<ArrivedFragment> frags;
    std::vector<Node> s;
  };
  std::vector<Scratch> scratch(parallel_row_threads((pixels + row - 1) / row, st.threads));
  for (auto& sc : scratch) sc.s.resize(static_cast<size_t>(n) + (laat ? 1 : 0));
  parallel_rows(pixels, row, st.threads, [&](unsigned thread, size_t p) {
    std::vector<ArrivedFragment>& frags = scratch[thread].frags;
    std::vector<Node>& s = scratch[thread].s;
    arrival_order(l, p, frags);
    const glm::vec3 bg = backdrop.at(p);
    glm::vec3 c = bg;
    if (tech == T::Ht || tech == T::FirstK) {
      c = ht_pixel(frags, s, n, bg, tech == T::Ht, st.htgs);
    } else if (tech == T::Unsorted) {
      for (const auto& f : frags) c = glm::vec3(f.colour) * f.colour.a + c * (1.0f - f.colour.a);
    } else if (tech == T::GlobalSort) {  // fragments keyed by their splat's centre: its order
      c = global_sort_pixel(frags, st.early_stop, bg);
    } else if (tech == T::Wboit) {
      c = wboit_pixel(frags, st, bg);
    } else {
      std::fill(s.begin(), s.end(), Node(0u));
      for (const auto& f : frags)
        insert_node(tech, s, n, glm::vec4(glm::vec3(f.colour) * f.colour.a, 1.0f - f.colour.a), f.depth, st.unguarded);
      c = tech == T::Mlab || tech == T::Umlab ? mlab_pixel(s, tech == T::Umlab, bg)
                                              : at_pixel(frags, s, relative, laat, st.unguarded, bg);
    }
    for (int k = 0; k < 3; ++k) m.rgb[p * 3 + k] = c[k];
  });
  return m;
}

}  // namespace oitbench::oit
