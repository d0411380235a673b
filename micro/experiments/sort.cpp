// sort: sorting N fragments per pixel (Brüll 2018 4.5, figures 4.7/4.8, tables A.1 and A.3;
// Knowles 2014 section 3, the register-based sort). Each pixel's N 64-bit fragments (32-bit depth
// key + RGBA8 payload) come from an SSBO filled on the CPU with the case's seed; a fragment or
// compute pass sorts them with one of the library's sorts (shaders/sorts/, the files the oit and
// stencil resolves run too) and writes them to a second SSBO; the CPU checks every pixel: keys in
// order, and the same multiset of (key, payload) pairs. Each row names the library file it ran
// and the hash of its text (`sort_source`).
#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "core/registry.hpp"
#include "gl/render_target.hpp"
#include "oit/capture/packed_fragment.hpp"
#include "oit/reference/metrics.hpp"
#include "shaders/sort/bindings.h"

namespace oitbench {

namespace {

using Fragment = PackedFragment;

// The sort algorithms: parameter value, its library file (shaders/<file>), the define that selects
// that file in shaders/sort/algorithms.glsl, the variant define the file reads, and which memory
// forms exist.
struct Algorithm {
  const char* variant;
  const char* file;
  const char* use_define;
  const char* extra_define;  // a define the algorithm's file reads, or nullptr
  bool has_local, has_registers;
  const char* why_not;  // why one form is missing
};

const std::vector<Algorithm>& algorithms() {
  static const std::vector<Algorithm> table = {
      // insertion-naive's write a[j+1] = key is chosen by `assign` (Table A.1): SORT_ASSIGN_*.
      {"insertion-naive", "sorts/insertion.glsl", "SORT_USE_INSERTION", nullptr, true, true, ""},
      {"insertion-v1", "sorts/insertion.glsl", "SORT_USE_INSERTION", "SORT_ASSIGN_LOOP", true, true, ""},
      {"insertion-v2", "sorts/insertion.glsl", "SORT_USE_INSERTION", "SORT_INSERTION_SWAP", true, true, ""},
      {"bubble", "sorts/bubble.glsl", "SORT_USE_BUBBLE", nullptr, true, true, ""},
      {"bubble-early", "sorts/bubble.glsl", "SORT_USE_BUBBLE", "SORT_BUBBLE_EARLY_OUT", true, true, ""},
      {"shell", "sorts/shell.glsl", "SORT_USE_SHELL", nullptr, true, true, ""},
      {"shell-offset", "sorts/shell.glsl", "SORT_USE_SHELL", "SORT_SHELL_OFFSET", true, true, ""},
      {"shell-register", "sorts/shell.glsl", "SORT_USE_SHELL", "SORT_SHELL_SWAP", true, true, ""},
      {"merge", "sorts/merge.glsl", "SORT_USE_MERGE", nullptr, true, false,
       "merge sort reads through cursors that depend on the keys: its array must be indexable, so it has no "
       "register form (memory=local only)"},
      {"bitonic", "sorts/bitonic.glsl", "SORT_USE_BITONIC", nullptr, true, true, ""},
      {"odd-even-merge", "sorts/odd_even_merge.glsl", "SORT_USE_ODD_EVEN_MERGE", nullptr, true, true, ""},
      {"bitonic-network", "sorts/network.glsl", "SORT_USE_NETWORK", "SORT_NETWORK_BITONIC", false, true,
       "bitonic-network is unrolled into literal indices by scripts/sort_networks.py: it has no local-memory form "
       "(memory=registers only)"},
      {"odd-even-merge-network", "sorts/network.glsl", "SORT_USE_NETWORK", "SORT_NETWORK_ODD_EVEN_MERGE", false, true,
       "odd-even-merge-network is unrolled into literal indices by scripts/sort_networks.py: it has no local-memory "
       "form (memory=registers only)"},
      {"rbs", "sorts/register_sort.glsl", "SORT_USE_REGISTER_SORT", nullptr, false, true,
       "rbs is Knowles 2014 Listing 5, an insertion network unrolled by hand with literal indices: it has no "
       "local-memory form (memory=registers only)"},
  };
  return table;
}

bool is_network(const Algorithm& a) { return std::string(a.use_define) == "SORT_USE_NETWORK"; }

constexpr const char* kInt64 = "GL_ARB_gpu_shader_int64";

const Algorithm& algorithm(const std::string& variant) {
  for (const auto& a : algorithms())
    if (variant == a.variant) return a;
  throw std::invalid_argument("sort: unknown variant '" + variant + "'");
}

std::vector<std::string> variant_names() {
  std::vector<std::string> v;
  for (const auto& a : algorithms()) v.push_back(a.variant);
  return v;
}

// N fragments per pixel, pixel-major. Keys are exact floats in [0, 1) (24-bit integers times 2^-24);
// payloads are random RGBA8.
std::vector<Fragment> generate_fragments(const std::string& keys, int n, size_t pixels, unsigned seed) {
  std::mt19937 rng(seed);
  auto random_key = [&] { return static_cast<float>(rng() >> 8) * (1.0f / 16777216.0f); };
  const float few[4] = {0.125f, 0.25f, 0.5f, 0.75f};
  std::vector<Fragment> frags(pixels * static_cast<size_t>(n));
  std::vector<float> pool(static_cast<size_t>(std::max(1, n / 2)));
  for (size_t p = 0; p < pixels; ++p) {
    Fragment* f = &frags[p * static_cast<size_t>(n)];
    if (keys == "duplicates")
      for (auto& v : pool) v = random_key();
    for (int i = 0; i < n; ++i) {
      float k = keys == "duplicates"     ? pool[rng() % pool.size()]
                : keys == "few-distinct" ? few[rng() % 4]
                                         : random_key();
      f[i] = {bits_of(k), static_cast<uint32_t>(rng())};
    }
    auto by_key = [](const Fragment& a, const Fragment& b) { return key_of(a) < key_of(b); };
    if (keys == "sorted") std::sort(f, f + n, by_key);
    if (keys == "reverse") std::sort(f, f + n, [&](const Fragment& a, const Fragment& b) { return by_key(b, a); });
  }
  return frags;
}

gl::Buffer make_storage(const void* data, size_t bytes) {
  auto b = gl::make_buffer();
  glNamedBufferStorage(b.get(), static_cast<GLsizeiptr>(bytes), data, 0);
  return b;
}

class SortCase final : public CaseInstance {
 public:
  SortCase(const ParamSet& p, CaseContext& ctx)
      : n_(static_cast<int>(p.get_int("n"))),
        compute_(p.get("stage") == "compute"),
        width_(ctx.width()),
        height_(ctx.height()),
        target_(ctx.width(), ctx.height(), GL_R32UI) {
    const Algorithm& a = algorithm(p.get("variant"));
    size_t pixels = static_cast<size_t>(width_) * static_cast<size_t>(height_);
    const size_t bytes = require_fragment_block(pixels * static_cast<size_t>(n_), "sort");

    Defines defines = {{"SORT_N", std::to_string(n_)},
                       {"SORT_N_LOG2", std::to_string(ceil_log2(n_))},
                       {p.get("memory") == "registers" ? "MEMORY_REGISTERS" : "MEMORY_LOCAL", ""},
                       {a.use_define, ""}};
    if (a.extra_define) defines.push_back({a.extra_define, ""});
    if (is_network(a) && p.get("compare") == "min-max") defines.push_back({"SORT_PACKED_KEY64", ""});
    if (std::string assign = p.get("assign"); std::string(a.variant) == "insertion-naive") {
      if (assign == "listing") assign = "direct";
      std::string define = "SORT_ASSIGN_" + assign;
      std::transform(define.begin(), define.end(), define.begin(),
                     [](char c) { return c == '-' ? '_' : std::toupper(c); });
      defines.push_back({define, ""});
    }
    sort_source_ = ctx.shaders().source_id(a.file);
    if (is_network(a)) sort_source_ += "+" + ctx.shaders().source_id("sorts/network_tables.glsl");
    program_ = compute_
                   ? ctx.build({{GL_COMPUTE_SHADER, "sort/sort.comp"}}, defines)
                   : ctx.build({{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "sort/sort.frag"}},
                               defines);
    GLuint prog = program_.get();
    glProgramUniform1i(prog, glGetUniformLocation(prog, "count"), n_);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "count_log2"), ceil_log2(n_));
    glProgramUniform1i(prog, glGetUniformLocation(prog, "zero"), 0);
    glProgramUniform2i(prog, glGetUniformLocation(prog, "image_size"), width_, height_);

    input_ = generate_fragments(p.get("keys"), n_, pixels, ctx.seed());
    in_ = make_storage(input_.data(), bytes);
    out_ = make_storage(nullptr, bytes);
  }

  void run(PassTimer& timer) override {
    glUseProgram(program_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SORT_BENCH_IN_BINDING, in_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SORT_BENCH_OUT_BINDING, out_.get());
    auto pass = timer.pass("sort");
    if (compute_) {
      glDispatchCompute(static_cast<GLuint>((width_ + 7) / 8), static_cast<GLuint>((height_ + 7) / 8), 1);
    } else {
      target_.bind();
      quad_.draw();
    }
  }

  std::map<std::string, std::string> metrics() const override { return {{"sort_source", sort_source_}}; }

  Validation validate() override {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<Fragment> got(input_.size());
    glGetNamedBufferSubData(out_.get(), 0, static_cast<GLsizeiptr>(got.size() * sizeof(Fragment)), got.data());
    long unsorted = 0, changed = 0;
    std::string first;
    auto pair_less = [](const Fragment& a, const Fragment& b) {
      return a.key_bits != b.key_bits ? a.key_bits < b.key_bits : a.rgba < b.rgba;
    };
    std::vector<Fragment> want(static_cast<size_t>(n_)), have(static_cast<size_t>(n_));
    for (int y = 0; y < height_; ++y)
      for (int x = 0; x < width_; ++x) {
        size_t base =
            (static_cast<size_t>(y) * static_cast<size_t>(width_) + static_cast<size_t>(x)) * static_cast<size_t>(n_);
        const Fragment* g = &got[base];
        std::string where = "pixel (" + std::to_string(x) + "," + std::to_string(y) + ")";
        for (int i = 1; i < n_; ++i)
          if (key_of(g[i - 1]) > key_of(g[i])) {
            if (unsorted++ == 0 && first.empty())
              first = where + ": key[" + std::to_string(i - 1) + "] = " + std::to_string(key_of(g[i - 1])) + " > key[" +
                      std::to_string(i) + "] = " + std::to_string(key_of(g[i]));
            break;
          }
        // Stable or not, the output must hold exactly the input's (key, payload) pairs.
        std::copy(&input_[base], &input_[base] + n_, want.begin());
        std::copy(g, g + n_, have.begin());
        std::sort(want.begin(), want.end(), pair_less);
        std::sort(have.begin(), have.end(), pair_less);
        for (int i = 0; i < n_; ++i)
          if (want[i].key_bits != have[i].key_bits || want[i].rgba != have[i].rgba) {
            if (changed++ == 0 && first.empty())
              first = where + ": the (key, payload) pairs differ from the input's (a pair lost, changed or duplicated)";
            break;
          }
      }
    Validation v;
    v.valid = unsorted == 0 && changed == 0;
    v.metrics["unsorted_pixels"] = std::to_string(unsorted);
    v.metrics["changed_pixels"] = std::to_string(changed);
    if (!v.valid)
      v.reason = std::to_string(unsorted) + " pixel(s) out of order, " + std::to_string(changed) +
                 " pixel(s) whose fragments differ from the input; first: " + first;
    return v;
  }

 private:
  int n_;
  bool compute_;
  int width_, height_;
  RenderTarget target_;
  FullscreenTriangle quad_;
  gl::Program program_;
  std::string sort_source_;
  std::vector<Fragment> input_;
  gl::Buffer in_, out_;
};

class SortExperiment final : public ExperimentOf<SortCase> {
 public:
  // 256x256: 65,536 pixels sort like the thesis' 640,000 (800x800) in the same shape, while a
  // local-memory insertion sort of 32 reverse-ordered keys still takes ~0.1 s per pass on llvmpipe.
  SortExperiment()
      : ExperimentOf("sort",
                     "sorting n 64-bit fragments per pixel (Brüll 2018 4.5, tables A.1/A.3; Knowles 2014 RBS) in a "
                     "fragment or compute pass, local-memory vs register forms; ms per pass",
                     {256, 256}, {128, 128}) {}
  std::vector<ParamSpec> params() const override {
    return {
        ParamSpec::choice("variant",
                          "the sort (shaders/sorts/<file>.glsl): insertion-naive (Listing 4.11), insertion-v1 "
                          "(select-loop write), insertion-v2 (Listing 4.12), bubble / bubble-early (Listing 4.10), "
                          "shell (4.13; miscompiled by llvmpipe), shell-offset (4.13 indexed like 4.11), "
                          "shell-register (4.14), merge (bottom-up), bitonic, odd-even-merge (networks as loops), "
                          "bitonic-network, odd-even-merge-network (the same networks fully unrolled, branchless "
                          "compare-exchanges: sorts/network.glsl), rbs (Knowles Listing 5)",
                          variant_names(), {}, {"insertion-naive", "insertion-v2", "rbs"}),
        // --quick stops at 16: rbs's 32-element network JITs for minutes on llvmpipe (once; Mesa's disk cache
        // keeps it).
        ParamSpec::integer("n", "fragments per pixel", 2, 32, {"4", "8", "12", "16", "20", "24", "28", "32"},
                           {"8", "16"}),
        ParamSpec::choice("stage", "full-screen fragment pass or compute pass (8x8 groups)", {"fragment", "compute"},
                          {}, {"fragment"}),
        ParamSpec::choice("memory",
                          "registers: loop bounds are the constant n (loops unroll, indices become constants); "
                          "local: bounds are a uniform equal to n (the array stays dynamically indexed)",
                          {"local", "registers"}),
        ParamSpec::choice("keys", "key distribution per pixel (CPU, from the seed)",
                          {"random", "sorted", "reverse", "duplicates", "few-distinct"}, {"random"}),
        ParamSpec::choice("assign",
                          "Table A.1: how insertion-naive writes a[j+1] = key: direct (the listing), loop (Listing "
                          "4.7), switch, if-else; `listing` = each variant as published",
                          {"listing", "direct", "loop", "switch", "if-else"}, {"listing"}),
        ParamSpec::choice("compare",
                          "the register networks' compare-exchange: min-max of the fragment as one 64-bit key (depth "
                          "key high, payload low; needs GL_ARB_gpu_shader_int64) or select (one comparison, two "
                          "selects)",
                          {"min-max", "select"}, {"min-max"})
            .only_when("variant", {"bitonic-network", "odd-even-merge-network"})};
  }
  std::vector<MetricSpec> metric_specs() const override {
    return {{"unsorted_pixels", ValueType::Integer, "", "pixels whose keys are out of order after the sort"},
            {"changed_pixels", ValueType::Integer, "", "pixels whose multiset of (key, payload) pairs changed"},
            oit::sort_source_metric()};
  }
  std::string unsupported_reason(const GlInfo& gl, const ParamSet& p) const override {
    const Algorithm& a = algorithm(p.get("variant"));
    if (is_network(a) && p.get("compare") == "min-max" && !gl.has_extension(kInt64))
      return std::string("compare=min-max reads the fragment as a 64-bit key: the driver lacks ") + kInt64 +
             " (compare=select works everywhere)";
    bool registers = p.get("memory") == "registers";
    if ((registers && !a.has_registers) || (!registers && !a.has_local)) return a.why_not;
    if (p.get("assign") != "listing" && std::string(a.variant) != "insertion-naive")
      return "assign chooses how Listing 4.11 writes a[j+1] (Table A.1); it applies to variant=insertion-naive only";
    return "";
  }
};

}  // namespace

void register_sort(Registry& registry) { registry.add(std::make_unique<SortExperiment>()); }

}  // namespace oitbench
