#include "oit/approx.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

// The one translation unit that compiles stb's PNG writer (a Debian header, not vendored).
#define STB_IMAGE_WRITE_IMPLEMENTATION
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wsign-compare"
#include <stb_image_write.h>
#pragma GCC diagnostic pop

#include <glm/gtc/matrix_transform.hpp>

#include "shaders/approx/bindings.h"
#include "gl/render_target.hpp"
#include "oit/gpu_mesh.hpp"
#include "oit/reference.hpp"
#include "oit/scene.hpp"
#include "oit/storage_layout.hpp"

namespace oitbench::oit {

namespace {

constexpr float kDepthEmpty = std::numeric_limits<float>::max();
constexpr unsigned kOneBits = 0x3F800000u;
// The GPU and its model differ by float rounding (fused multiply-adds, exp/log/pow), and MLAB's
// RGBA8 nodes can round the other way at a half step and carry that through later merges.
constexpr double kModelTolerance = 3.0 / 255.0;
constexpr int kSpinCap = 1 << 16;

const std::vector<std::string> kNames = {"MLAB", "UMLAB", "AT", "HAT", "UAT", "UHAT", "LAAT", "WBOIT", "unsorted"};

std::string fmt(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

// --- The node encodings of shaders/approx/nodes.glsl, on the CPU --------------------------------
using Node = glm::uvec2;

float unorm8(unsigned c, int k) { return static_cast<float>((c >> (8 * k)) & 0xffu) / 255.0f; }
unsigned pack_unorm(float v) { return static_cast<unsigned>(std::nearbyint(std::clamp(v, 0.0f, 1.0f) * 255.0f)); }
unsigned pack4(glm::vec4 v) {
  return pack_unorm(v.x) | pack_unorm(v.y) << 8 | pack_unorm(v.z) << 16 | pack_unorm(v.w) << 24;
}
glm::vec4 unpack4(unsigned c) { return {unorm8(c, 0), unorm8(c, 1), unorm8(c, 2), unorm8(c, 3)}; }

float node_depth(Node n) { return n.y == 0u ? kDepthEmpty : std::bit_cast<float>(n.y - 1u); }
unsigned encode_depth(float z) { return z >= kDepthEmpty ? 0u : std::bit_cast<unsigned>(z) + 1u; }
glm::vec4 mlab_value(Node n) {
  glm::vec4 k = unpack4(n.x);
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

// --- The insertions of shaders/approx/insert.frag, on the CPU -----------------------------------
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
  float tc = t[compress] * t[remove];
  if (compress == n) {
    s[remove] = at_node(tc, d[n]);
  } else {
    s[compress] = at_node(tc, d[compress]);
    if (remove != n) s[remove] = at_node(a, z);
  }
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
  float tc = t[compress] * t[remove];
  if (compress == n) {
    s[remove] = at_node(tc, d[n]);
  } else {
    s[compress] = at_node(tc, d[compress]);
    if (remove != n) s[remove] = at_node(a, z);
  }
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

struct Frag {
  glm::vec4 colour;
  float depth;
};

// One pixel's fragments in arrival order: the linked list prepends, so its reverse.
void arrival_order(const HostLists& l, size_t pixel, std::vector<Frag>& out) {
  out.clear();
  for (unsigned i = l.heads[pixel]; i != kListEnd && i < l.nodes.size() && out.size() <= l.nodes.size(); i = l.next[i])
    out.push_back({unpack4(l.nodes[i].x), std::bit_cast<float>(l.nodes[i].y)});
  std::reverse(out.begin(), out.end());
}

}  // namespace

const std::vector<std::string>& approx_technique_names() { return kNames; }
bool is_approx_technique(const std::string& name) {
  return std::find(kNames.begin(), kNames.end(), name) != kNames.end();
}
ApproxTechnique parse_approx_technique(const std::string& name) {
  auto it = std::find(kNames.begin(), kNames.end(), name);
  if (it == kNames.end()) throw std::invalid_argument("unknown approximate technique '" + name + "'");
  return static_cast<ApproxTechnique>(it - kNames.begin());
}

std::vector<ParamSpec> approx_params() {
  using K = ParamSpec::Kind;
  const std::vector<std::string> arrays = {"MLAB", "UMLAB", "AT", "HAT", "UAT", "UHAT", "LAAT"};
  const std::vector<std::string> guarded = {"AT", "HAT", "UAT", "UHAT", "LAAT", "WBOIT"};
  std::vector<ParamSpec> ps = {
      {"nodes", "nodes per pixel of MLAB, UMLAB, AT, HAT, UAT, UHAT, LAAT (the thesis: 4-16)", {"8"}, {}, {}, K::Integer, 2, 64},
      {"storage", "node storage of the per-pixel array techniques (shaders/storage/)", {"ssbo"}, {},
       {"ssbo", "texture3d", "interleaved"}},
      {"wboit_weight", "WBOIT depth weight: none (weighted average), eq7 (view distance), eq10 (window depth)",
       {"eq7"}, {}, {"none", "eq7", "eq10"}},
      {"sync", "per-pixel insertion: spinlock (Listing 4.3, capped) or interlock (ARB_fragment_shader_interlock)",
       {"spinlock"}, {}, {"spinlock", "interlock"}},
      {"guard", "numeric guards of the AT family and WBOIT (off: the deliberately unguarded variant the hard-case "
                "tests use)",
       {"on"}, {}, {"on", "off"}},
      {"flicker_runs", "frames kept for the flicker metric (per-pixel variance across runs; 0: off)", {"4"}, {}, {},
       K::Integer, 0, 64},
  };
  ps[0].only_when("technique", arrays);
  ps[1].only_when("technique", arrays);
  ps[2].only_when("technique", {"WBOIT"});
  ps[3].only_when("technique", arrays);
  ps[4].only_when("technique", guarded);
  ps[5].only_when("technique", approx_technique_names());
  return ps;
}

ApproxModel approx_model(const HostLists& l, glm::vec3 bg, const ApproxSettings& st) {
  size_t pixels = l.heads.size();
  const int n = st.nodes;
  ApproxModel m;
  m.rgb.resize(pixels * 3);
  std::vector<Frag> frags;
  std::vector<Node> s(n);
  using T = ApproxTechnique;
  const T tech = st.technique;
  const bool laat = tech == T::Laat, relative = tech == T::Uat || tech == T::Uhat || laat;
  if (laat) s.resize(n + 1);  // the head slot
  for (size_t p = 0; p < pixels; ++p) {
    arrival_order(l, p, frags);
    glm::vec3 c = bg;
    if (tech == T::Unsorted) {
      for (const auto& f : frags) c = glm::vec3(f.colour) * f.colour.a + c * (1.0f - f.colour.a);
    } else if (tech == T::Wboit) {
      glm::vec4 acc(0.0f);
      float reveal = 1.0f;
      for (const auto& f : frags) {
        float w = f.colour.a * wboit_weight(st.weight, f.depth, st.near_far);
        acc += glm::vec4(glm::vec3(f.colour) * w, w);
        reveal *= 1.0f - f.colour.a;
      }
      if (!frags.empty()) {
        glm::vec3 average = glm::vec3(acc) / (st.unguarded ? acc.a : std::clamp(acc.a, 1e-4f, 5e4f));
        c = average * (1.0f - reveal) + bg * reveal;
      }
    } else {
      std::fill(s.begin(), s.end(), Node(0u));
      for (const auto& f : frags) {
        glm::vec4 ct(glm::vec3(f.colour) * f.colour.a, 1.0f - f.colour.a);
        switch (tech) {
          case T::Mlab: insert_mlab(s, n, ct, f.depth); break;
          case T::Umlab: insert_umlab(s, n, ct, f.depth); break;
          case T::At: insert_at(s, n, ct.w, f.depth, false, st.unguarded); break;
          case T::Hat: insert_at(s, n, ct.w, f.depth, true, st.unguarded); break;
          case T::Uat: insert_uat(s, n, ct.w, f.depth); break;
          case T::Laat: insert_laat(s, n, ct.w, f.depth); break;
          default: insert_uhat(s, n, ct.w, f.depth, st.unguarded); break;
        }
      }
      if (tech == T::Mlab || tech == T::Umlab) {
        std::vector<std::pair<float, glm::vec4>> nodes;
        for (const Node& node : s) nodes.push_back({node_depth(node), mlab_value(node)});
        if (tech == T::Umlab)  // the resolve's insertion sort: stable
          std::stable_sort(nodes.begin(), nodes.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
        glm::vec3 acc(0.0f);
        float t = 1.0f;
        for (const auto& [z, ct] : nodes) {
          acc += t * glm::vec3(ct);
          t *= ct.w;
        }
        c = acc + t * bg;
      } else {
        glm::vec4 acc(0.0f);
        for (const auto& f : frags) {
          float w = f.colour.a * visibility(s, f.depth, relative, laat);
          acc += glm::vec4(glm::vec3(f.colour) * w, w);
        }
        float total = visibility(s, kDepthEmpty, relative, laat), opacity = 1.0f - total;
        if (!st.unguarded && acc.a > opacity * (1.0f + 1e-5f) + 1e-6f) acc = glm::vec4(glm::vec3(acc) * (opacity / acc.a), acc.a);
        c = glm::vec3(acc) + total * bg;
      }
    }
    for (int k = 0; k < 3; ++k) m.rgb[p * 3 + k] = c[k];
  }
  return m;
}

ApproxError approx_error(const std::vector<float>& rgb, const std::vector<double>& ref) {
  ApproxError e;
  double sum = 0;
  size_t off = 0, pixels = ref.size() / 3;
  for (size_t p = 0; p < pixels; ++p) {
    bool bad = false;
    for (int k = 0; k < 3; ++k) {
      double d = std::abs(static_cast<double>(rgb[p * 3 + k]) - ref[p * 3 + k]);
      if (!std::isfinite(d)) d = 1.0;  // a NaN counts as fully wrong here; finiteness is checked apart
      sum += d * d;
      e.max_abs_error = std::max(e.max_abs_error, d);
      bad |= d > 1.0 / 255.0;
    }
    off += bad;
  }
  e.rmse = pixels ? std::sqrt(sum / (pixels * 3.0)) : 0.0;
  e.psnr = e.rmse > 0 ? 20.0 * std::log10(1.0 / e.rmse) : 999.0;
  e.frac_pixels_off = pixels ? static_cast<double>(off) / pixels : 0.0;
  return e;
}

void write_png(const std::string& path, const std::vector<float>& rgb, int width, int height, float scale) {
  std::vector<unsigned char> bytes(static_cast<size_t>(width) * height * 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int k = 0; k < 3; ++k) {
        float v = rgb[(static_cast<size_t>(height - 1 - y) * width + x) * 3 + k] * scale;
        bytes[(static_cast<size_t>(y) * width + x) * 3 + k] =
            static_cast<unsigned char>(std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f : 255.0f);
      }
  if (!stbi_write_png(path.c_str(), width, height, 3, bytes.data(), width * 3))
    throw std::runtime_error("cannot write " + path);
}

namespace {

class ApproxCase final : public OitCase {
 public:
  ApproxCase(const ParamSet& p, CaseContext& ctx)
      : width_(ctx.width()),
        height_(ctx.height()),
        scene_(load_scene(p.get("scene"))),
        out_(ctx.width(), ctx.height(), GL_RGBA32F),
        accum_(ctx.width(), ctx.height(), GL_RGBA32F),
        flicker_runs_(static_cast<int>(p.get_int("flicker_runs"))),
        dump_(ctx.image_stem()) {
    settings_.technique = parse_approx_technique(p.get("technique"));
    settings_.nodes = static_cast<int>(p.get_int("nodes"));
    settings_.weight = p.get("wboit_weight");
    settings_.unguarded = p.get("guard") == "off";
    using T = ApproxTechnique;
    const T tech = settings_.technique;
    arrays_ = tech != T::Wboit && tech != T::Unsorted;
    at_family_ = arrays_ && tech != T::Mlab && tech != T::Umlab;
    bool interlock = p.get("sync") == "interlock";
    if (arrays_ && interlock && !ctx.gl().has_extension("GL_ARB_fragment_shader_interlock"))
      throw Unsupported("sync=interlock needs GL_ARB_fragment_shader_interlock");

    const View& view = scene_.view(p.get("view"));
    Mesh mesh = build_mesh(scene_, view, p.get("detail") == "small" ? Detail::Small : Detail::Full);
    mesh_ = std::make_unique<GpuMesh>(mesh);
    glm::mat4 vp = view_projection(view, mesh, static_cast<float>(width_) / height_);
    // The planes back out of the perspective matrix (glm::perspective's layout).
    glm::mat4 pm = vp * glm::inverse(glm::lookAt(view.eye, view.target, view.up));
    settings_.near_far = {pm[3][2] / (pm[2][2] - 1.0f), pm[3][2] / (pm[2][2] + 1.0f)};

    // The fragments, once: the exact reference and every model work on these.
    size_t pixels = static_cast<size_t>(width_) * height_;
    lists_ = make_fragment_storage(parse_capture_storage(p.get("capture")), ctx, pixels * 4, false);
    auto capture = build_capture_programs(*lists_, ctx,
                                          {{GL_VERTEX_SHADER, "oit/capture.vert"}, {GL_FRAGMENT_SHADER, "oit/capture.frag"}});
    for (const auto& prog : capture) set_view_proj(prog, vp);
    out_.bind();
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    lists_->capture(ids(capture), [&] { mesh_->draw(); });
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    host_ = lists_->read_back();
    lists_.reset();  // its pool is not needed for timing

    Defines d = {{"TECH_" + upper(p.get("technique")), ""}, {"SPIN_CAP", std::to_string(kSpinCap)}};
    if (settings_.unguarded) d.push_back({"APPROX_UNGUARDED", ""});
    if (interlock) d.push_back({"SYNC_INTERLOCK", ""});
    if (arrays_) {
      std::string storage = p.get("storage");
      layout_ = StorageLayout::parse(storage == "interleaved" ? "interleaved-4x4-a4" : storage);
      // LAAT keeps its list head in one more slot per pixel.
      int slots = settings_.nodes + (tech == T::Laat ? 1 : 0);
      if (layout_.kind == StorageLayout::Kind::Interleaved && slots % layout_.align) layout_.align = 1;
      for (const auto& x : layout_.defines(width_, height_, slots)) d.push_back(x);
      storage_ = std::make_unique<StorageResources>(layout_, width_, height_, slots);
      locks_ = gl::make_texture(GL_TEXTURE_2D);
      glTextureStorage2D(locks_.get(), 1, GL_R32UI, width_, height_);
      stats_ = gl::make_buffer();
      glNamedBufferStorage(stats_.get(), sizeof(unsigned), nullptr, GL_DYNAMIC_STORAGE_BIT);
      insert_ = ctx.build({{GL_VERTEX_SHADER, "oit/capture.vert"}, {GL_FRAGMENT_SHADER, "approx/insert.frag"}}, d);
      set_view_proj(insert_, vp);
      if (at_family_) {
        blend_ = ctx.build({{GL_VERTEX_SHADER, "oit/capture.vert"}, {GL_FRAGMENT_SHADER, "approx/at_blend.frag"}}, d);
        set_view_proj(blend_, vp);
      }
      resolve_ = ctx.build({{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "approx/resolve.frag"}}, d);
    } else if (tech == T::Wboit) {
      d.push_back({"WEIGHT_" + upper(settings_.weight), ""});
      blend_ = ctx.build({{GL_VERTEX_SHADER, "oit/capture.vert"}, {GL_FRAGMENT_SHADER, "approx/wboit_accum.frag"}}, d);
      set_view_proj(blend_, vp);
      glProgramUniform2f(blend_.get(), glGetUniformLocation(blend_.get(), "nearFar"), settings_.near_far.x,
                         settings_.near_far.y);
      reveal_ = gl::make_texture(GL_TEXTURE_2D);
      glTextureStorage2D(reveal_.get(), 1, GL_R32F, width_, height_);
      glNamedFramebufferTexture(accum_.framebuffer(), GL_COLOR_ATTACHMENT1, reveal_.get(), 0);
      resolve_ = ctx.build({{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "approx/wboit_resolve.frag"}}, d);
    } else {
      blend_ = ctx.build({{GL_VERTEX_SHADER, "oit/capture.vert"}, {GL_FRAGMENT_SHADER, "approx/unsorted.frag"}}, d);
      set_view_proj(blend_, vp);
    }
    if (resolve_) {
      glProgramUniform3f(resolve_.get(), glGetUniformLocation(resolve_.get(), "background"), scene_.background.r,
                         scene_.background.g, scene_.background.b);
    }
  }

  void set_view_projection(const glm::mat4& view_proj) override {
    for (const gl::Program* prog : {&insert_, &blend_})
      if (*prog) set_view_proj(*prog, view_proj);
  }
  GLuint result_texture() override { return out_.color_texture(); }
  unsigned max_frags() const override { return arrays_ ? static_cast<unsigned>(settings_.nodes) : 0; }

  void run(PassTimer& timer) override {
    using T = ApproxTechnique;
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    if (arrays_) {
      {
        auto t = timer.pass("insert");
        storage_->clear();
        glClearTexImage(locks_.get(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
        glClearNamedBufferData(stats_.get(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
        out_.bind();
        glDisable(GL_BLEND);
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        storage_->bind();
        glBindImageTexture(APPROX_LOCK_IMAGE_UNIT, locks_.get(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, APPROX_STATS_BINDING, stats_.get());
        glUseProgram(insert_.get());
        mesh_->draw();
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        StorageResources::barrier();
      }
      if (at_family_) {
        auto t = timer.pass("blend");
        accum_.bind();
        const float zero[4] = {0, 0, 0, 0};
        glClearNamedFramebufferfv(accum_.framebuffer(), GL_COLOR, 0, zero);
        glEnable(GL_BLEND);
        glBlendFunc(GL_ONE, GL_ONE);
        glUseProgram(blend_.get());
        mesh_->draw();
        glDisable(GL_BLEND);
      }
      auto t = timer.pass("resolve");
      out_.bind();
      glBindTextureUnit(APPROX_ACCUM_UNIT, accum_.color_texture());
      glUseProgram(resolve_.get());
      quad_.draw();
    } else if (settings_.technique == T::Wboit) {
      {
        auto t = timer.pass("accumulate");
        accum_.bind();
        const GLenum bufs[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
        glNamedFramebufferDrawBuffers(accum_.framebuffer(), 2, bufs);
        const float zero[4] = {0, 0, 0, 0}, one[4] = {1, 1, 1, 1};
        glClearNamedFramebufferfv(accum_.framebuffer(), GL_COLOR, 0, zero);
        glClearNamedFramebufferfv(accum_.framebuffer(), GL_COLOR, 1, one);
        glEnable(GL_BLEND);
        glBlendFunci(0, GL_ONE, GL_ONE);
        glBlendFunci(1, GL_ZERO, GL_ONE_MINUS_SRC_COLOR);
        glUseProgram(blend_.get());
        mesh_->draw();
        glDisable(GL_BLEND);
      }
      auto t = timer.pass("resolve");
      out_.bind();
      glBindTextureUnit(APPROX_ACCUM_UNIT, accum_.color_texture());
      glBindTextureUnit(APPROX_REVEAL_UNIT, reveal_.get());
      glUseProgram(resolve_.get());
      quad_.draw();
    } else {
      auto t = timer.pass("blend");
      out_.bind();
      const float bg[4] = {scene_.background.r, scene_.background.g, scene_.background.b, 1.0f};
      glClearNamedFramebufferfv(out_.framebuffer(), GL_COLOR, 0, bg);
      glEnable(GL_BLEND);
      glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
      glUseProgram(blend_.get());
      mesh_->draw();
      glDisable(GL_BLEND);
    }
    // Outside the timed passes: the frames the flicker metric compares.
    if (flicker_runs_ > 0) {
      frames_.push_back(rgb_of(out_.read_rgba32f()));
      if (static_cast<int>(frames_.size()) > flicker_runs_) frames_.erase(frames_.begin());
    }
  }

  Validation validate() override {
    Validation v;
    auto& m = v.metrics;
    std::vector<float> rgb = rgb_of(out_.read_rgba32f());
    ListStats stats = list_stats(host_);
    auto ref = composite_reference(host_, scene_.background);
    ApproxModel model = approx_model(host_, scene_.background, settings_);
    ApproxError err = approx_error(rgb, ref);
    m["total_fragments"] = std::to_string(stats.total_fragments);
    m["peak_depth"] = std::to_string(stats.peak_depth);
    m["mean_depth"] = fmt(stats.mean_depth);
    m["polygons"] = std::to_string(mesh_->polygons());
    m["rmse"] = fmt(err.rmse);
    m["psnr"] = fmt(err.psnr);
    m["max_abs_error"] = fmt(err.max_abs_error);
    m["frac_pixels_off"] = fmt(err.frac_pixels_off);
    m["model_rmse"] = fmt(approx_error(model.rgb, std::vector<double>(ref.begin(), ref.end())).rmse);

    size_t nonfinite = 0, out_of_range = 0, model_off = 0;
    double model_max = 0;
    std::string first_off;
    for (size_t i = 0; i < rgb.size(); ++i) {
      if (!std::isfinite(rgb[i])) ++nonfinite;
      else if (rgb[i] < -1.0 / 255.0 || rgb[i] > 1.0 + 2.0 / 255.0) ++out_of_range;
      double d = std::abs(static_cast<double>(rgb[i]) - model.rgb[i]);
      if (!std::isfinite(d) && std::isfinite(rgb[i]) != std::isfinite(model.rgb[i])) d = 1.0;
      if (!std::isfinite(d)) d = 0.0;  // both non-finite: the model predicts the failure
      model_max = std::max(model_max, d);
      if (d > kModelTolerance && model_off++ == 0) {
        size_t px = i / 3;
        first_off = "pixel (" + std::to_string(px % width_) + "," + std::to_string(px / width_) + ") channel " +
                    std::to_string(i % 3) + ": GPU " + fmt(rgb[i]) + ", model " + fmt(model.rgb[i]);
      }
    }
    m["nonfinite"] = std::to_string(nonfinite);
    m["model_max_diff"] = fmt(model_max);
    unsigned capped = 0;
    if (arrays_) {
      glGetNamedBufferSubData(stats_.get(), 0, sizeof(unsigned), &capped);
      m["capped_updates"] = std::to_string(capped);
    }
    if (frames_.size() >= 2) {
      // Per-pixel variance across the frames (mean over channels), averaged and at its peak.
      double sum = 0, peak = 0;
      size_t changed = 0;
      size_t k = frames_.size();
      for (size_t i = 0; i < rgb.size(); i += 3) {
        double var_px = 0;
        for (int c = 0; c < 3; ++c) {
          double mean = 0, sq = 0;
          for (const auto& f : frames_) mean += f[i + c];
          mean /= k;
          for (const auto& f : frames_) sq += (f[i + c] - mean) * (f[i + c] - mean);
          var_px += sq / k / 3.0;
        }
        sum += var_px;
        peak = std::max(peak, var_px);
        changed += var_px > 0;
      }
      m["flicker"] = fmt(sum / (rgb.size() / 3));
      m["flicker_max"] = fmt(peak);
      m["flicker_pixels"] = std::to_string(changed);
    }
    if (!dump_.empty()) {
      write_png(dump_ + ".png", rgb, width_, height_);
      std::vector<float> diff(rgb.size());
      for (size_t i = 0; i < rgb.size(); ++i) diff[i] = std::abs(rgb[i] - static_cast<float>(ref[i]));
      write_png(dump_ + "-diff8.png", diff, width_, height_, 8.0f);
    }

    std::vector<std::string> problems;
    if (!stats.error.empty()) problems.push_back(stats.error);
    if (nonfinite) problems.push_back(std::to_string(nonfinite) + " non-finite channel value(s) (NaN or Inf)");
    if (out_of_range) problems.push_back(std::to_string(out_of_range) + " channel value(s) outside [0, 1]");
    if (capped) problems.push_back(std::to_string(capped) + " insertion(s) gave up on the spinlock (lost)");
    if (model_off)
      problems.push_back(std::to_string(model_off) + " channel value(s) differ from the technique's CPU model by more "
                         "than 3/255; first: " + first_off);
    v.valid = problems.empty();
    for (const auto& s : problems) v.reason += (v.reason.empty() ? "" : "; ") + s;
    return v;
  }

 private:
  static std::string upper(std::string s) {
    for (auto& ch : s) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
    return s;
  }
  static void set_view_proj(const gl::Program& prog, const glm::mat4& vp) {
    glProgramUniformMatrix4fv(prog.get(), glGetUniformLocation(prog.get(), "viewProj"), 1, GL_FALSE, &vp[0][0]);
  }
  static std::vector<float> rgb_of(const std::vector<float>& rgba) {
    std::vector<float> rgb(rgba.size() / 4 * 3);
    for (size_t p = 0; p < rgba.size() / 4; ++p)
      for (int k = 0; k < 3; ++k) rgb[p * 3 + k] = rgba[p * 4 + k];
    return rgb;
  }

  int width_, height_;
  SceneDesc scene_;
  RenderTarget out_, accum_;
  FullscreenTriangle quad_;
  std::unique_ptr<GpuMesh> mesh_;
  std::unique_ptr<FragmentStorage> lists_;
  HostLists host_;
  ApproxSettings settings_;
  bool arrays_ = false, at_family_ = false;
  StorageLayout layout_;
  std::unique_ptr<StorageResources> storage_;
  gl::Texture locks_, reveal_;
  gl::Buffer stats_;
  gl::Program insert_, blend_, resolve_;
  int flicker_runs_;
  std::string dump_;
  std::vector<std::vector<float>> frames_;
};

}  // namespace

std::unique_ptr<OitCase> make_approx_case(const ParamSet& p, CaseContext& ctx) {
  return std::make_unique<ApproxCase>(p, ctx);
}

}  // namespace oitbench::oit
