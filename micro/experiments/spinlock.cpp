// spinlock: per-pixel locks for fragment insertion (Brüll 2018, section 4.2, Listings 4.1-4.3)
// against the hardware's fragment shader interlock. `layers` overlapping screen-filling layers per
// draw all append to the same per-pixel array under the lock (shaders/spinlock/spinlock.frag).
// Hang-prone: Listing 4.1 deadlocks SIMT GPUs, so every case runs in a child process under the
// watchdog, and every spin loop gives up after `spin_cap` attempts (counted as capped updates).
#include <algorithm>
#include <cctype>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/registry.hpp"
#include "oit/storage/storage_layout.hpp"
#include "shaders/spinlock/bindings.h"

namespace oitbench {

namespace {

// The same function as spin_value() in shaders/spinlock/spinlock.frag.
std::uint32_t spin_value(int x, int y, int layer) {
  return (static_cast<std::uint32_t>(x) * 2654435761u) ^ (static_cast<std::uint32_t>(y) * 40503u) ^
         (static_cast<std::uint32_t>(layer) * 2246822519u);
}

// The interlock extension this driver offers (define suffix), or "" when it has none.
std::string interlock_flavour(const GlInfo& gl) {
  if (gl.has_extension("GL_ARB_fragment_shader_interlock")) return "ARB";
  if (gl.has_extension("GL_NV_fragment_shader_interlock")) return "NV";
  if (gl.has_extension("GL_INTEL_fragment_shader_ordering")) return "INTEL";
  return "";
}

gl::Texture r32ui_image(int width, int height) {
  auto t = gl::make_texture(GL_TEXTURE_2D);
  glTextureStorage2D(t.get(), 1, GL_R32UI, width, height);
  return t;
}

class SpinlockCase final : public CaseInstance {
 public:
  SpinlockCase(const ParamSet& p, CaseContext& ctx)
      : layers_(static_cast<int>(p.get_int("layers"))),
        draws_(static_cast<int>(p.get_int("draws"))),
        capacity_(layers_ * draws_),
        width_(ctx.width()),
        height_(ctx.height()),
        array_(StorageLayout::parse("ssbo"), width_, height_, capacity_),
        locks_(r32ui_image(width_, height_)),
        counts_(r32ui_image(width_, height_)),
        stats_(gl::make_buffer()),
        fbo_(storage_only_framebuffer(width_, height_)),
        vao_(gl::make_vertex_array()) {
    std::string variant = p.get("variant");
    std::string define;
    if (variant == "interlock") {
      auto flavour = interlock_flavour(ctx.gl());
      if (flavour.empty()) throw Unsupported("no fragment shader interlock extension");
      define = "VARIANT_INTERLOCK_" + flavour;
      metrics_["lock_extension"] =
          flavour == "INTEL" ? "GL_INTEL_fragment_shader_ordering" : "GL_" + flavour + "_fragment_shader_interlock";
    } else {
      define = "VARIANT_" + variant;
      std::transform(define.begin(), define.end(), define.begin(),
                     [](char c) { return c == '-' ? '_' : static_cast<char>(std::toupper(c)); });
      metrics_["lock_extension"] = "none";
    }
    Defines defines = StorageLayout::parse("ssbo").defines(width_, height_, capacity_);
    defines.push_back({define, ""});
    defines.push_back({"SPIN_CAP", p.get("spin_cap") + "u"});
    program_ =
        ctx.build({{GL_VERTEX_SHADER, "common/layers.vert"}, {GL_FRAGMENT_SHADER, "spinlock/spinlock.frag"}}, defines);
    glProgramUniform1i(program_.get(), glGetUniformLocation(program_.get(), "zero"), 0);
    layer_base_ = glGetUniformLocation(program_.get(), "layerBase");
    glNamedBufferStorage(stats_.get(), sizeof(std::uint32_t), nullptr, GL_DYNAMIC_STORAGE_BIT);
  }

  void run(PassTimer& timer) override {
    {
      auto t = timer.pass("clear");
      array_.clear();
      glClearTexImage(locks_.get(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
      glClearTexImage(counts_.get(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
      glClearNamedBufferData(stats_.get(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
    }
    auto t = timer.pass("insert");
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
    glViewport(0, 0, width_, height_);
    glUseProgram(program_.get());
    glBindVertexArray(vao_.get());
    array_.bind();
    glBindImageTexture(SPINLOCK_LOCK_IMAGE_UNIT, locks_.get(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    glBindImageTexture(SPINLOCK_COUNT_IMAGE_UNIT, counts_.get(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SPINLOCK_STATS_BINDING, stats_.get());
    for (int d = 0; d < draws_; ++d) {
      glUniform1i(layer_base_, d * layers_);
      glDrawArrays(GL_TRIANGLES, 0, 6 * layers_);
      StorageResources::barrier();
    }
  }

  // Exact: every pixel's count is layers * draws and its array holds exactly the entries
  // {(spin_value(x, y, l), l) : l < layers * draws} in any order (compared as multisets).
  Validation validate() override {
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
    auto nodes = array_.read_back();
    std::vector<std::uint32_t> counts(static_cast<std::size_t>(width_) * height_);
    glGetTextureImage(counts_.get(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT,
                      static_cast<GLsizei>(counts.size() * sizeof(std::uint32_t)), counts.data());
    std::uint32_t capped = 0;
    glGetNamedBufferSubData(stats_.get(), 0, sizeof capped, &capped);

    const auto expected = static_cast<std::uint32_t>(capacity_);
    long long lost = 0, bad_pixels = 0;
    std::string first;
    std::vector<StorageNode> want(capacity_), got(capacity_);
    for (int y = 0; y < height_; ++y)
      for (int x = 0; x < width_; ++x) {
        std::size_t px = static_cast<std::size_t>(y) * width_ + x;
        std::uint32_t c = counts[px];
        std::string where = "pixel (" + std::to_string(x) + "," + std::to_string(y) + ")";
        if (c != expected) {
          if (c < expected) lost += expected - c;
          if (bad_pixels++ == 0)
            first = where + " count " + std::to_string(c) + ", expected " + std::to_string(expected);
          continue;
        }
        for (int l = 0; l < capacity_; ++l) want[l] = {spin_value(x, y, l), static_cast<std::uint32_t>(l)};
        std::copy_n(nodes.begin() + static_cast<std::ptrdiff_t>(px * capacity_), capacity_, got.begin());
        std::sort(got.begin(), got.end());
        std::sort(want.begin(), want.end());
        if (got != want) {
          auto mismatch = std::mismatch(got.begin(), got.end(), want.begin());
          if (bad_pixels++ == 0)
            first = where + " holds (" + std::to_string((*mismatch.first)[0]) + ", layer " +
                    std::to_string((*mismatch.first)[1]) + ") where the CPU reference has (" +
                    std::to_string((*mismatch.second)[0]) + ", layer " + std::to_string((*mismatch.second)[1]) + ")";
        }
      }
    Validation v;
    v.metrics["lost_updates"] = std::to_string(lost);
    v.metrics["capped_updates"] = std::to_string(capped);
    v.metrics["mismatched_pixels"] = std::to_string(bad_pixels);
    v.valid = bad_pixels == 0 && capped == 0;
    if (capped > 0)
      v.reason = std::to_string(capped) + " update(s) gave up at spin_cap and were lost (" + std::to_string(lost) +
                 " missing from the counts); ";
    if (bad_pixels > 0)
      v.reason += std::to_string(bad_pixels) + " pixel(s) differ from the CPU reference; first: " + first;
    return v;
  }

  std::map<std::string, std::string> metrics() const override { return metrics_; }

 private:
  int layers_, draws_, capacity_, width_, height_;
  StorageResources array_;
  gl::Texture locks_, counts_;
  gl::Buffer stats_;
  gl::Framebuffer fbo_;
  gl::VertexArray vao_;
  gl::Program program_;
  GLint layer_base_ = -1;
  std::map<std::string, std::string> metrics_;
};

class SpinlockExperiment final : public ExperimentOf<SpinlockCase> {
 public:
  SpinlockExperiment()
      : ExperimentOf("spinlock",
                     "per-pixel critical sections (Bruell 2018, Listings 4.1-4.3): naive, loop and helper-guard "
                     "spinlocks and fragment shader interlock; layers append to a per-pixel array; capped and lost "
                     "updates counted",
                     {512, 512}, {64, 64}) {}
  std::vector<ParamSpec> params() const override {
    // The compared parameter last: the variants of one grid point run one after another.
    return {ParamSpec::integer("layers", "overlapping screen-filling layers per draw, each inserting into every pixel",
                               1, 256, {"8", "32"}, {"8"}),
            ParamSpec::integer("draws", "draws per repetition (the array holds layers * draws entries)", 1, 64, {"1"}),
            ParamSpec::integer("spin_cap", "attempts before a fragment gives up (its update is lost and counted)", 1,
                               1 << 30, {"65536"}),
            ParamSpec::choice("variant",
                              "naive (Listing 4.1), loop (4.2), helper-guard (4.3), interlock (ARB/NV/INTEL "
                              "extension), no-release (deliberately broken: never unlocks; for tests)",
                              {"naive", "loop", "helper-guard", "interlock", "no-release"},
                              {"naive", "loop", "helper-guard", "interlock"})};
  }
  std::vector<MetricSpec> metric_specs() const override {
    return {{"lost_updates", ValueType::Integer, "", "writes that did not land"},
            {"capped_updates", ValueType::Integer, "", "insertions that gave up on the spinlock after SPIN_CAP tries"},
            {"mismatched_pixels", ValueType::Integer, "", "pixels that differ from the CPU reference"},
            {"lock_extension", ValueType::Text, "", "the interlock extension used, or none"}};
  }
  bool hang_prone() const override { return true; }
  std::string unsupported_reason(const GlInfo& gl, const ParamSet& p) const override {
    if (p.get("variant") == "interlock" && interlock_flavour(gl).empty())
      return "needs GL_ARB_fragment_shader_interlock, GL_NV_fragment_shader_interlock or "
             "GL_INTEL_fragment_shader_ordering; " +
             gl.renderer + " has none";
    if (p.get_int("layers") * p.get_int("draws") > 2048) return "layers * draws above 2048 entries per pixel";
    return "";
  }
};

}  // namespace

void register_spinlock(Registry& registry) { registry.add(std::make_unique<SpinlockExperiment>()); }

}  // namespace oitbench
