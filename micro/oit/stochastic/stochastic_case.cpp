// The oit experiment's STOCHASTIC case (moments.hpp): stochastic transparency with
// samples_per_pixel coverage samples, validated against stochastic_model (moment_model.hpp), which
// draws the same masks from the same hash for the fragments' recorded MSAA coverage.
#include <algorithm>

#include "oit/case_support.hpp"
#include "oit/moments/captured_view.hpp"
#include "shaders/stochastic/bindings.h"

namespace oitbench::oit {

namespace {

// The GPU sums each sample in float where the model sums in double: far below 1/255.
constexpr double kStochasticTolerance = 2.0 / 255.0;

std::vector<GLint> sample_counts(GLenum format) {
  GLint n = 0;
  glGetInternalformativ(GL_TEXTURE_2D_MULTISAMPLE, format, GL_NUM_SAMPLE_COUNTS, 1, &n);
  std::vector<GLint> counts(static_cast<size_t>(std::max(n, 0)));
  if (n > 0) glGetInternalformativ(GL_TEXTURE_2D_MULTISAMPLE, format, GL_SAMPLES, n, counts.data());
  return counts;
}

class StochasticCase final : public CapturedViewCase {
 public:
  StochasticCase(const ParamSet& p, CaseContext& ctx)
      : CapturedViewCase(p, ctx), run_seed_(ctx.seed()), total_(ctx.width(), ctx.height(), GL_R32F) {
    const int samples = static_cast<int>(p.get_int("samples_per_pixel"));
    // The most MSAA samples the driver renders RGBA32F and 32-bit float depth with that divide the
    // count, at most 16 (hash.glsl's masks shift within one uint); the rest comes from further passes
    // (Enderton et al.: more passes, more samples).
    auto colour = sample_counts(GL_RGBA32F), depth = sample_counts(GL_DEPTH_COMPONENT32F);
    int best = 0;
    for (GLint c : colour)
      if (c >= 2 && c <= std::min(samples, 16) && samples % c == 0 &&
          std::find(depth.begin(), depth.end(), c) != depth.end())
        best = std::max(best, static_cast<int>(c));
    if (best == 0)
      throw Unsupported(technique_ +
                        " needs multisampled RGBA32F and DEPTH_COMPONENT32F textures with a sample count "
                        "dividing " +
                        std::to_string(samples) + "; the driver has none");
    setup_ = {width_, height_, best, samples / best, 0, 0};  // the model on every core

    colour_ = gl::make_texture(GL_TEXTURE_2D_MULTISAMPLE);
    glTextureStorage2DMultisample(colour_.get(), best, GL_RGBA32F, width_, height_, GL_TRUE);
    depth_ = gl::make_texture(GL_TEXTURE_2D_MULTISAMPLE);
    glTextureStorage2DMultisample(depth_.get(), best, GL_DEPTH_COMPONENT32F, width_, height_, GL_TRUE);
    msaa_ = gl::make_framebuffer();
    glNamedFramebufferTexture(msaa_.get(), GL_COLOR_ATTACHMENT0, colour_.get(), 0);
    glNamedFramebufferTexture(msaa_.get(), GL_DEPTH_ATTACHMENT, depth_.get(), 0);
    if (glCheckNamedFramebufferStatus(msaa_.get(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw Unsupported(technique_ + ": the " + std::to_string(best) +
                        "x MSAA framebuffer is incomplete on this driver");
    bytes_ = best * (16 + 4) + 4;

    Defines d = view_.fx->geometry_defines();
    for (auto& x : view_.fx->depth_sampler_defines()) d.push_back(x);
    d.push_back({"MSAA_SAMPLES", std::to_string(best)});
    d.push_back({"STOCHASTIC_PASSES", std::to_string(setup_.passes)});
    const std::string vert = "scene/scene.vert";
    coverage_ = ctx.build({{GL_VERTEX_SHADER, vert}, {GL_FRAGMENT_SHADER, "stochastic/coverage.frag"}}, d);
    depth_pass_ = ctx.build({{GL_VERTEX_SHADER, vert}, {GL_FRAGMENT_SHADER, "stochastic/depth.frag"}}, d);
    accumulate_ = ctx.build({{GL_VERTEX_SHADER, vert}, {GL_FRAGMENT_SHADER, "stochastic/accumulate.frag"}}, d);
    alpha_ = ctx.build({{GL_VERTEX_SHADER, vert}, {GL_FRAGMENT_SHADER, "stochastic/alpha.frag"}}, d);
    resolve_ =
        ctx.build({{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "stochastic/resolve.frag"}}, d);
    projected_ = {&coverage_, &depth_pass_, &accumulate_, &alpha_};
    set_view_projection(view_.view_proj);
    record_coverage();
  }

  void run(PassTimer& timer) override {
    if (!begin_run(timer, {&depth_pass_, &accumulate_, &alpha_})) return;
    setup_.frame_seed = stochastic_frame_seed(run_seed_, frame_++);
    glDisable(GL_CULL_FACE);
    {
      auto t = timer.pass("stochastic");
      glBindFramebuffer(GL_FRAMEBUFFER, msaa_.get());
      glViewport(0, 0, width_, height_);
      glEnable(GL_MULTISAMPLE);
      const float zero[4] = {0, 0, 0, 0};
      glClearNamedFramebufferfv(msaa_.get(), GL_COLOR, 0, zero);
      glEnable(GL_DEPTH_TEST);
      glProgramUniform1ui(depth_pass_.get(), glGetUniformLocation(depth_pass_.get(), "frameSeed"), setup_.frame_seed);
      for (int pass = 0; pass < setup_.passes; ++pass) {
        const float far_depth = 1.0f;
        glDepthMask(GL_TRUE);  // before the clear, which the depth write mask also masks
        glClearNamedFramebufferfv(msaa_.get(), GL_DEPTH, 0, &far_depth);
        glDepthFunc(GL_LESS);
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        glDisable(GL_BLEND);
        glProgramUniform1ui(depth_pass_.get(), glGetUniformLocation(depth_pass_.get(), "passIndex"),
                            static_cast<GLuint>(pass));
        glUseProgram(depth_pass_.get());
        view_.mesh->draw();
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glDepthMask(GL_FALSE);
        glDepthFunc(GL_LEQUAL);
        glEnable(GL_BLEND);
        glBlendFunc(GL_ONE, GL_ONE);
        glUseProgram(accumulate_.get());
        view_.mesh->draw();
      }
      glDepthMask(GL_TRUE);
      glDepthFunc(GL_LESS);
      glDisable(GL_DEPTH_TEST);
      glDisable(GL_BLEND);
    }
    {
      auto t = timer.pass("alpha");
      total_.bind_cleared(1, 1, 1, 1);
      glEnable(GL_BLEND);
      glBlendFunc(GL_ZERO, GL_ONE_MINUS_SRC_COLOR);
      glUseProgram(alpha_.get());
      view_.mesh->draw();
      glDisable(GL_BLEND);
    }
    resolve_pass(timer, resolve_, [&] {
      glBindTextureUnit(STOCHASTIC_ACCUM_UNIT, colour_.get());
      glBindTextureUnit(STOCHASTIC_TOTAL_UNIT, total_.color_texture());
    });
  }

  Validation validate() override {
    ModelValidation mv = validate_against(
        [&] { return stochastic_model(coverage_fragments_, view_.ref->host, view_.ref->backdrop, setup_); },
        kStochasticTolerance);
    mv.v.metrics["msaa_samples"] = std::to_string(setup_.msaa_samples);
    if (coverage_lost_) mv.problems.push_back("the MSAA coverage record lost fragments");
    return conclude_against(mv, kStochasticTolerance, 0, " (same masks)");
  }

 private:
  // Every fragment's MSAA coverage, once (captured_view.hpp).
  void record_coverage() {
    coverage_lost_ = !oit::record_coverage(view_, msaa_.get(), width_, height_, coverage_, coverage_fragments_);
  }

  uint32_t run_seed_;
  RenderTarget total_;
  gl::Texture colour_, depth_;
  gl::Framebuffer msaa_;
  gl::Program coverage_, depth_pass_, accumulate_, alpha_, resolve_;
  StochasticSetup setup_;
  std::vector<CoverageFragment> coverage_fragments_;
  bool coverage_lost_ = false;
  uint32_t frame_ = 0;
};

}  // namespace

std::unique_ptr<OitCase> make_stochastic_case(const ParamSet& p, CaseContext& ctx) {
  return std::make_unique<StochasticCase>(p, ctx);
}

}  // namespace oitbench::oit
