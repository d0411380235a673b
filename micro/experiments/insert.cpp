// insert: inserting one element into a sorted array of `size` fragments, repeated `repeat` times
// per pixel (Brüll 2018 4.4, Table A.2, Listings 4.8, 4.9 and A.1). Each pixel starts from a sorted
// array uploaded from the CPU; shaders/insert/insert.frag inserts `repeat` hashed new elements, each
// overwriting the current minimum, and writes the array back; the CPU replays the same insertions
// and compares every fragment bit for bit.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "core/registry.hpp"
#include "gl/render_target.hpp"
#include "oit/capture/packed_fragment.hpp"
#include "shaders/sort/bindings.h"

namespace oitbench {

namespace {

using Fragment = PackedFragment;

// shaders/insert/insert.frag's mix32 and new_element, bit for bit.
uint32_t mix32(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

Fragment new_element(const std::string& keys, uint32_t pixel, int round, uint32_t seed) {
  uint32_t h = mix32(pixel ^ mix32(static_cast<uint32_t>(round) + seed * 0x9e3779b9u));
  float key = keys == "front"  ? -1.0f - static_cast<float>(round)
              : keys == "back" ? 1.0f + static_cast<float>(round)
                               : static_cast<float>(h >> 8) * (1.0f / 16777216.0f);
  return {bits_of(key), mix32(h)};
}

// All three listings leave the same array (in each the new element stops before an equal key), so
// one reference serves them: move a[0] up while its right neighbour has a smaller key.
void insert_reference(Fragment* a, int size) {
  for (int i = 0; i < size - 1 && key_of(a[i]) > key_of(a[i + 1]); ++i) std::swap(a[i], a[i + 1]);
}

const char* function_of(const std::string& variant) {
  if (variant == "early-out") return "insert_early_out";
  if (variant == "no-early-out") return "insert_no_early_out";
  if (variant == "two-moves") return "insert_two_moves";
  throw std::invalid_argument("insert: unknown variant '" + variant + "'");
}

class InsertCase final : public CaseInstance {
 public:
  InsertCase(const ParamSet& p, CaseContext& ctx)
      : size_(static_cast<int>(p.get_int("size"))),
        repeat_(static_cast<int>(p.get_int("repeat"))),
        keys_(p.get("keys")),
        seed_(ctx.seed()),
        width_(ctx.width()),
        height_(ctx.height()),
        target_(ctx.width(), ctx.height(), GL_R32UI) {
    size_t pixels = static_cast<size_t>(width_) * static_cast<size_t>(height_);
    const size_t bytes = require_fragment_block(pixels * static_cast<size_t>(size_), "insert");
    std::string keys_define = keys_ == "front" ? "KEYS_FRONT" : keys_ == "back" ? "KEYS_BACK" : "KEYS_RANDOM";
    program_ = ctx.build({{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "insert/insert.frag"}},
                         {{"SORT_N", std::to_string(size_)},
                          {"SORT_N_LOG2", std::to_string(ceil_log2(size_))},
                          {p.get("memory") == "registers" ? "MEMORY_REGISTERS" : "MEMORY_LOCAL", ""},
                          {"INSERT_ALGORITHM", function_of(p.get("variant"))},
                          {keys_define, ""}});
    GLuint prog = program_.get();
    glProgramUniform1i(prog, glGetUniformLocation(prog, "count"), size_);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "count_log2"), ceil_log2(size_));
    glProgramUniform1i(prog, glGetUniformLocation(prog, "zero"), 0);
    glProgramUniform2i(prog, glGetUniformLocation(prog, "image_size"), width_, height_);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "repeat"), repeat_);
    glProgramUniform1ui(prog, glGetUniformLocation(prog, "seed"), seed_);

    // Sorted starting arrays, keys in [0, 1) exact (24-bit integers times 2^-24).
    std::mt19937 rng(seed_);
    initial_.resize(pixels * static_cast<size_t>(size_));
    for (size_t px = 0; px < pixels; ++px) {
      Fragment* a = &initial_[px * static_cast<size_t>(size_)];
      for (int i = 0; i < size_; ++i)
        a[i] = {bits_of(static_cast<float>(rng() >> 8) * (1.0f / 16777216.0f)), static_cast<uint32_t>(rng())};
      std::sort(a, a + size_, [](const Fragment& x, const Fragment& y) { return key_of(x) < key_of(y); });
    }
    in_ = gl::make_buffer();
    glNamedBufferStorage(in_.get(), static_cast<GLsizeiptr>(bytes), initial_.data(), 0);
    out_ = gl::make_buffer();
    glNamedBufferStorage(out_.get(), static_cast<GLsizeiptr>(bytes), nullptr, 0);
  }

  void run(PassTimer& timer) override {
    glUseProgram(program_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SORT_BENCH_IN_BINDING, in_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SORT_BENCH_OUT_BINDING, out_.get());
    target_.bind();
    auto pass = timer.pass("insert");
    quad_.draw();
  }

  Validation validate() override {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<Fragment> got(initial_.size());
    glGetNamedBufferSubData(out_.get(), 0, static_cast<GLsizeiptr>(got.size() * sizeof(Fragment)), got.data());
    long bad = 0;
    std::string first;
    std::vector<Fragment> want(static_cast<size_t>(size_));
    for (int y = 0; y < height_; ++y)
      for (int x = 0; x < width_; ++x) {
        uint32_t pixel = static_cast<uint32_t>(y * width_ + x);
        size_t base = static_cast<size_t>(pixel) * static_cast<size_t>(size_);
        std::copy(&initial_[base], &initial_[base] + size_, want.begin());
        for (int r = 0; r < repeat_; ++r) {
          want[0] = new_element(keys_, pixel, r, seed_);
          insert_reference(want.data(), size_);
        }
        for (int i = 0; i < size_; ++i)
          if (got[base + i].key_bits != want[i].key_bits || got[base + i].rgba != want[i].rgba) {
            if (bad++ == 0)
              first = "pixel (" + std::to_string(x) + "," + std::to_string(y) + ")[" + std::to_string(i) + "] = (" +
                      std::to_string(key_of(got[base + i])) + ", " + std::to_string(got[base + i].rgba) +
                      "), CPU reference (" + std::to_string(key_of(want[i])) + ", " + std::to_string(want[i].rgba) +
                      ")";
            break;
          }
      }
    Validation v;
    v.valid = bad == 0;
    v.metrics["mismatched_pixels"] = std::to_string(bad);
    if (!v.valid) v.reason = std::to_string(bad) + " pixel(s) differ from the CPU reference; first: " + first;
    return v;
  }

 private:
  int size_, repeat_;
  std::string keys_;
  uint32_t seed_;
  int width_, height_;
  RenderTarget target_;
  FullscreenTriangle quad_;
  gl::Program program_;
  std::vector<Fragment> initial_;
  gl::Buffer in_, out_;
};

class InsertExperiment final : public ExperimentOf<InsertCase> {
 public:
  InsertExperiment()
      : ExperimentOf("insert",
                     "inserting one element into a sorted per-pixel array, repeated per pixel (Brüll 2018 4.4, Table "
                     "A.2): early out (Listing 4.8) vs none (4.9) vs two moves (A.1); ms per pass",
                     {256, 256}, {128, 128}) {}
  std::vector<ParamSpec> params() const override {
    return {ParamSpec::choice("variant",
                              "early-out: swap, stop when in place (Listing 4.8); no-early-out: swap where out of "
                              "order (4.9); two-moves: two moves instead of a swap (A.1)",
                              {"early-out", "no-early-out", "two-moves"}),
            ParamSpec::integer("size", "fragments in the sorted array", 2, 32,
                               {"4", "8", "12", "16", "20", "24", "28", "32"}, {"8", "32"}),
            ParamSpec::integer("repeat", "insertions per pixel (the thesis: 128 Village, 16 Powerplant)", 1, 100000,
                               {"128"}, {"32"}),
            ParamSpec::choice("keys",
                              "new keys: random (uniform; as the array keeps the largest keys most stop early), "
                              "front (smaller than all: stop at once), back (larger than all: travel the whole array)",
                              {"random", "front", "back"}, {"random", "back"}, {"random"}),
            ParamSpec::choice("memory", "registers: constant loop bounds (unrolled); local: uniform bounds",
                              {"registers", "local"}, {"registers"})};
  }
  std::vector<MetricSpec> metric_specs() const override {
    return {{"mismatched_pixels", ValueType::Integer, "", "pixels whose array differs from the CPU reference"}};
  }
};

}  // namespace

void register_insert(Registry& registry) { registry.add(std::make_unique<InsertExperiment>()); }

}  // namespace oitbench
