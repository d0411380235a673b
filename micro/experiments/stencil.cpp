// stencil: the full-screen resolve only where transparent fragments landed (Brüll 2018, section
// 4.6, Listing 4.15, Tables A.4/A.5). A capture-like pass writes `layers` fragments per pixel
// into a band covering `coverage` percent of the screen (and, in the stencil variant, a stencil
// mask); the resolve then runs over the whole screen, with or without the stencil test.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/registry.hpp"
#include "gl/render_target.hpp"
#include "oit/reference/metrics.hpp"
#include "oit/storage/storage_layout.hpp"

namespace oitbench {

namespace {

constexpr float kBackground[4] = {0.25f, 0.5f, 0.75f, 1.0f};  // the "opaque geometry"

// The same function as stencil_fragment() in shaders/stencil/fragment.glsl.
StorageNode stencil_fragment(int x, int y, int l, int layers) {
  std::uint32_t h = (static_cast<std::uint32_t>(x) * 2654435761u) ^ (static_cast<std::uint32_t>(y) * 40503u) ^
                    (static_cast<std::uint32_t>(l) * 2246822519u);
  std::uint32_t alpha = 32u + (h >> 25);
  return {(h & 0x00ffffffu) | (alpha << 24), static_cast<std::uint32_t>((l + 3 * x + 7 * y) % layers)};
}

// Rows [0, covered_rows) hold transparent geometry: at least one row, whole rows only.
int covered_rows(int height, int coverage_percent) { return std::max(1, (height * coverage_percent + 50) / 100); }

class StencilCase final : public CaseInstance {
 public:
  StencilCase(const ParamSet& p, CaseContext& ctx)
      : stencil_(p.get("variant") == "stencil"),
        sort_(p.get("resolve") == "sort"),
        nodes_(static_cast<int>(p.get_int("nodes"))),
        layers_(static_cast<int>(p.get_int("layers"))),
        rows_(covered_rows(ctx.height(), static_cast<int>(p.get_int("coverage")))),
        target_(ctx.width(), ctx.height(), GL_RGBA32F, true),
        storage_(StorageLayout::parse("ssbo"), ctx.width(), ctx.height(), nodes_),
        vao_(gl::make_vertex_array()) {
    Defines defines = StorageLayout::parse("ssbo").defines(ctx.width(), ctx.height(), nodes_);
    Defines capture_defines = defines;
    capture_defines.push_back({"LAYERS", std::to_string(layers_)});
    capture_ = ctx.build({{GL_VERTEX_SHADER, "common/layers.vert"}, {GL_FRAGMENT_SHADER, "stencil/capture.frag"}},
                         capture_defines);
    defines.push_back({sort_ ? "RESOLVE_SORT" : "RESOLVE_BLEND", ""});
    if (sort_) sort_source_ = ctx.shaders().source_id("sorts/insertion.glsl");  // what resolve.frag includes
    resolve_ = ctx.build({{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "stencil/resolve.frag"}},
                         defines);
    for (GLuint prog : {capture_.get(), resolve_.get()})
      glProgramUniform1i(prog, glGetUniformLocation(prog, "zero"), 0);
    glProgramUniform1f(capture_.get(), glGetUniformLocation(capture_.get(), "coverageTop"),
                       -1.0f + 2.0f * static_cast<float>(rows_) / static_cast<float>(ctx.height()));
  }

  void run(PassTimer& timer) override {
    target_.bind();
    {
      auto t = timer.pass("clear");
      glClearColor(kBackground[0], kBackground[1], kBackground[2], kBackground[3]);
      glClearStencil(0);
      glClear(GL_COLOR_BUFFER_BIT | (stencil_ ? GL_STENCIL_BUFFER_BIT : 0));
      storage_.clear();
    }
    storage_.bind();
    glBindVertexArray(vao_.get());
    {
      auto t = timer.pass("capture");
      glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);  // capture writes only nodes (and stencil)
      if (stencil_) {
        glEnable(GL_STENCIL_TEST);
        glStencilFunc(GL_ALWAYS, 1, 0xFF);
        glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
      }
      glUseProgram(capture_.get());
      glDrawArrays(GL_TRIANGLES, 0, 6 * layers_);
      glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
      StorageResources::barrier();
    }
    auto t = timer.pass("resolve");
    if (stencil_) {
      glStencilFunc(GL_EQUAL, 1, 0xFF);
      glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    }
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_ONE, GL_SRC_ALPHA, GL_ZERO, GL_SRC_ALPHA);  // alpha keeps the remaining transmittance
    glUseProgram(resolve_.get());
    quad_.draw();
    glDisable(GL_BLEND);
    glDisable(GL_STENCIL_TEST);
  }

  // resolve=sort runs the library's insertion sort (shaders/sorts/insertion.glsl); blend sorts nothing.
  std::map<std::string, std::string> metrics() const override {
    if (!sort_) return {};
    return {{"sort_source", sort_source_}};
  }

  // Outside the band every pixel must still be the background, bit for bit; inside, the
  // front-to-back composite of the pixel's layers over the background (CPU reference, float
  // tolerance 1e-5: the driver may contract multiply-adds).
  Validation validate() override {
    auto px = target_.read_rgba32f();
    long inside_bad = 0, outside_bad = 0;
    std::string first;
    std::vector<StorageNode> frags(layers_);
    for (int y = 0; y < target_.height(); ++y)
      for (int x = 0; x < target_.width(); ++x) {
        float ref[4] = {kBackground[0], kBackground[1], kBackground[2], kBackground[3]};
        const bool inside = y < rows_;
        if (inside) {
          for (int l = 0; l < layers_; ++l) frags[l] = stencil_fragment(x, y, l, layers_);
          if (sort_)  // depth keys are a permutation: no ties
            std::sort(frags.begin(), frags.end(),
                      [](const StorageNode& a, const StorageNode& b) { return a[1] < b[1]; });
          float colour[3] = {0, 0, 0}, transmittance = 1.0f;
          for (const auto& f : frags) {
            float a = static_cast<float>(f[0] >> 24) / 255.0f;
            for (int k = 0; k < 3; ++k)
              colour[k] += transmittance * a * (static_cast<float>((f[0] >> (8 * k)) & 0xffu) / 255.0f);
            transmittance *= 1.0f - a;
          }
          for (int k = 0; k < 3; ++k) ref[k] = colour[k] + kBackground[k] * transmittance;
          ref[3] = kBackground[3] * transmittance;
        }
        const float* got = &px[(static_cast<std::size_t>(y) * target_.width() + x) * 4];
        for (int k = 0; k < 4; ++k) {
          bool bad = inside ? std::fabs(got[k] - ref[k]) > 1e-5f : got[k] != ref[k];
          if (!bad) continue;
          if (inside_bad + outside_bad == 0)
            first = "pixel (" + std::to_string(x) + "," + std::to_string(y) + ")[" + std::to_string(k) +
                    "] = " + std::to_string(got[k]) + ", CPU reference " + std::to_string(ref[k]) +
                    (inside ? " (inside the coverage)" : " (outside the coverage: must be untouched)");
          (inside ? inside_bad : outside_bad)++;
          break;
        }
      }
    Validation v;
    v.valid = inside_bad + outside_bad == 0;
    v.metrics["mismatched_pixels"] = std::to_string(inside_bad + outside_bad);
    v.metrics["touched_outside"] = std::to_string(outside_bad);
    v.metrics["covered_pixels"] = std::to_string(static_cast<long>(rows_) * target_.width());
    if (!v.valid)
      v.reason = std::to_string(inside_bad) + " pixel(s) inside and " + std::to_string(outside_bad) +
                 " outside the coverage differ from the CPU reference; first: " + first;
    return v;
  }

 private:
  bool stencil_, sort_;
  int nodes_, layers_, rows_;
  RenderTarget target_;
  StorageResources storage_;
  FullscreenTriangle quad_;
  gl::VertexArray vao_;
  gl::Program capture_, resolve_;
  std::string sort_source_;
};

class StencilExperiment final : public ExperimentOf<StencilCase> {
 public:
  StencilExperiment()
      : ExperimentOf("stencil",
                     "stencil-masked full-screen resolve (Bruell 2018, section 4.6, Tables A.4/A.5): resolve only "
                     "where the capture pass drew (stencil) or everywhere (no-stencil), for a band covering "
                     "`coverage` % of the screen",
                     {800, 800}, {128, 128}) {}  // the thesis's
  std::vector<ParamSpec> params() const override {
    // The compared parameter last: stencil and no-stencil of one grid point are interleaved together.
    return {ParamSpec::integer("coverage", "percent of the screen's rows that receive transparent fragments", 1, 100,
                               {"1", "10", "50", "100"}),
            ParamSpec::choice("resolve",
                              "blend: composite the nodes in storage order (Table A.4); sort: insertion sort "
                              "by depth first (Table A.5)",
                              {"blend", "sort"}, {}, {"blend"}),
            ParamSpec::integer("nodes", "nodes per pixel that the resolve reads", 1, 32, {"8"}, {"4"}),
            ParamSpec::integer("layers", "transparent layers per covered pixel (at most nodes)", 1, 32, {"4"}, {"4"}),
            ParamSpec::choice("variant",
                              "no-stencil: resolve every pixel; stencil: capture writes a stencil mask, the resolve "
                              "runs where it is 1 (Listing 4.15)",
                              {"no-stencil", "stencil"})};
  }
  std::vector<MetricSpec> metric_specs() const override {
    return {{"mismatched_pixels", ValueType::Integer, "", "pixels that differ from the CPU reference"},
            {"touched_outside", ValueType::Integer, "", "pixels outside the coverage the resolve wrote"},
            {"covered_pixels", ValueType::Integer, "", "pixels inside the coverage"},
            oit::sort_source_metric()};
  }
  std::string unsupported_reason(const GlInfo&, const ParamSet& p) const override {
    if (p.get_int("layers") > p.get_int("nodes"))
      return "layers=" + p.get("layers") + " exceeds nodes=" + p.get("nodes") + " (one node per layer)";
    return "";
  }
};

}  // namespace

void register_stencil(Registry& registry) { registry.add(std::make_unique<StencilExperiment>()); }

}  // namespace oitbench
