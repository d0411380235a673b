// The oit experiment's WOIT case (wavelets.hpp): a coefficient pass, a weighted colour pass and a
// resolve (shaders/wavelets/), validated against woit_model (wavelet_model.hpp).
#include "oit/case_support.hpp"
#include "oit/moments/captured_view.hpp"
#include "oit/wavelets/wavelet_model.hpp"
#include "shaders/wavelets/bindings.h"

namespace oitbench::oit {

namespace {

// The Haar reconstruction is well conditioned (a sum of at most log2(N) + 1 terms, no solve): the GPU
// and the model part only where float and double put a fragment's warped depth on different sides of
// a cell boundary, or by the float sums' and exp's rounding; the cosine series only by rounding. The
// tolerance is per channel.
constexpr double kWaveletTolerance = 2.0 / 255.0;

}  // namespace

std::vector<ParamSpec> wavelet_params() {
  return {
      ParamSpec::choice("wavelet_coeffs",
                        "coefficients per pixel: the Haar scaling function (the total absorbance) and the "
                        "wavelets of log2(N) levels, i.e. the absorbance in N depth cells",
                        {"8", "16", "32"}, {"16"}),
      ParamSpec::choice(
          "wavelet_basis",
          "the basis the absorbance is projected onto: haar (the paper's wavelets) or cosine (a smooth "
          "comparison, not a wavelet: sqrt(2) cos(pi k x), the community code's Fourier basis in half-range form)",
          {"haar", "cosine"}, {"haar"}),
      ParamSpec::choice("wavelet_bits", "storage of the coefficients, RGBA32F or RGBA16F layers (4 coefficients each)",
                        {"32", "16"}, {"32"}),
  };
}

namespace {

class WoitCase final : public CapturedViewCase {
 public:
  WoitCase(const ParamSet& p, CaseContext& ctx)
      : CapturedViewCase(p, ctx), accum_(ctx.width(), ctx.height(), GL_RGBA32F) {
    s_.basis = p.get("wavelet_basis") == "cosine" ? WaveletBasis::Cosine : WaveletBasis::Haar;
    s_.coeffs = static_cast<int>(p.get_int("wavelet_coeffs"));
    s_.bits = static_cast<int>(p.get_int("wavelet_bits"));
    s_.near_far = view_.near_far;
    require_depth_bounds(view_, p.get("technique"));
    s_.depth_range = view_.depth_range;
    make_targets();
    if (s_.bits == 16) s_.half_truncates = blend_truncates_half(ctx);
    Defines d = view_.fx->geometry_defines();
    for (auto& x : view_.fx->depth_sampler_defines()) d.push_back(x);
    d.push_back({"WAVELET_COEFFS", std::to_string(s_.coeffs)});
    if (s_.basis == WaveletBasis::Cosine) d.push_back({"WAVELET_COSINE", ""});
    coeff_pass_ =
        ctx.build({{GL_VERTEX_SHADER, "scene/scene.vert"}, {GL_FRAGMENT_SHADER, "wavelets/coefficients.frag"}}, d);
    blend_pass_ = ctx.build({{GL_VERTEX_SHADER, "scene/scene.vert"}, {GL_FRAGMENT_SHADER, "wavelets/blend.frag"}}, d);
    resolve_ =
        ctx.build({{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "wavelets/resolve.frag"}}, d);
    projected_ = {&coeff_pass_, &blend_pass_};
    for (const gl::Program* prog : {&coeff_pass_, &blend_pass_}) {
      set_view_proj(*prog, view_.view_proj);
      glProgramUniform2f(prog->get(), glGetUniformLocation(prog->get(), "nearFar"), s_.near_far.x, s_.near_far.y);
      glProgramUniform2f(prog->get(), glGetUniformLocation(prog->get(), "depthRange"), s_.depth_range.x,
                         s_.depth_range.y);
    }
  }

  void run(PassTimer& timer) override {
    if (!begin_run(timer, {&coeff_pass_, &blend_pass_})) return;
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    const float zero[4] = {0, 0, 0, 0};
    {
      auto t = timer.pass("coefficients");
      glBindFramebuffer(GL_FRAMEBUFFER, coeff_fbo_.get());
      glViewport(0, 0, width_, height_);
      for (GLint i = 0; i < layers(); ++i) glClearNamedFramebufferfv(coeff_fbo_.get(), GL_COLOR, i, zero);
      glEnable(GL_BLEND);
      glBlendFunc(GL_ONE, GL_ONE);
      glUseProgram(coeff_pass_.get());
      view_.mesh->draw();
    }
    {
      auto t = timer.pass("blend");
      accum_.bind_cleared(0, 0, 0, 0);
      glBindTextureUnit(WAVELETS_COEFFS_UNIT, coeffs_.get());
      glUseProgram(blend_pass_.get());
      view_.mesh->draw();
      glDisable(GL_BLEND);
    }
    resolve_pass(timer, resolve_, [&] {
      glBindTextureUnit(WAVELETS_COEFFS_UNIT, coeffs_.get());
      glBindTextureUnit(WAVELETS_ACCUM_UNIT, accum_.color_texture());
    });
  }

  Validation validate() override {
    ModelValidation mv =
        validate_against([&] { return woit_model(view_.ref->host, view_.ref->backdrop, s_); }, kWaveletTolerance);
    mv.v.metrics["model_off_channels"] = std::to_string(mv.check.off);
    if (s_.bits == 16) mv.v.metrics["half_blend_rounding"] = s_.half_truncates ? "toward-zero" : "nearest";
    // Where float and double warp a fragment into different cells, the transmittance of the
    // fragments behind it in that pixel moves by up to its cell's share of its absorbance: up to
    // 1% of the channels may differ; the wrong-result fault changes 12.5% of the pixels.
    return conclude_against(mv, kWaveletTolerance, mv.rgb.size() / 100);
  }

 private:
  GLint layers() const { return s_.coeffs / 4; }

  // How the blender rounds a sum into a half-float target: 1 + 3/4096 lies between the halves 1 and
  // 1 + 1/1024, nearer the second; round-to-nearest keeps that, truncation gives 1 (llvmpipe and
  // lavapipe truncate). The model rounds the 16-bit sums the same way.
  bool blend_truncates_half(CaseContext& ctx) {
    gl::Texture probe = gl::make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(probe.get(), 1, GL_RGBA16F, 1, 1);
    gl::Framebuffer fbo = gl::make_framebuffer();
    glNamedFramebufferTexture(fbo.get(), GL_COLOR_ATTACHMENT0, probe.get(), 0);
    gl::Program prog =
        ctx.build({{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "wavelets/half_probe.frag"}}, {});
    glProgramUniform1f(prog.get(), glGetUniformLocation(prog.get(), "addend"), 3.0f / 4096.0f);
    const float one[4] = {1, 1, 1, 1};
    glClearNamedFramebufferfv(fbo.get(), GL_COLOR, 0, one);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo.get());
    glViewport(0, 0, 1, 1);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    glUseProgram(prog.get());
    quad_.draw();
    glDisable(GL_BLEND);
    float px[4] = {0, 0, 0, 0};
    glGetTextureImage(probe.get(), 0, GL_RGBA, GL_FLOAT, sizeof(px), px);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return px[0] < 1.0f + 0.5f / 1024.0f;
  }

  // The coefficients: one 2D array texture, 4 per layer, every layer a colour attachment of one pass.
  void make_targets() {
    GLint draw_buffers = 0, attachments = 0;
    glGetIntegerv(GL_MAX_DRAW_BUFFERS, &draw_buffers);
    glGetIntegerv(GL_MAX_COLOR_ATTACHMENTS, &attachments);
    if (std::min(draw_buffers, attachments) < layers())
      throw Unsupported(technique_ + " wavelet_coeffs=" + std::to_string(s_.coeffs) + " needs " +
                        std::to_string(layers()) + " draw buffers; the driver has " +
                        std::to_string(std::min(draw_buffers, attachments)));
    const bool half = s_.bits == 16;
    coeffs_ = gl::make_texture(GL_TEXTURE_2D_ARRAY);
    glTextureStorage3D(coeffs_.get(), 1, half ? GL_RGBA16F : GL_RGBA32F, width_, height_, layers());
    coeff_fbo_ = gl::make_framebuffer();
    std::vector<GLenum> bufs;
    for (GLint i = 0; i < layers(); ++i) {
      glNamedFramebufferTextureLayer(coeff_fbo_.get(), GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i), coeffs_.get(), 0,
                                     i);
      bufs.push_back(GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i));
    }
    glNamedFramebufferDrawBuffers(coeff_fbo_.get(), static_cast<GLsizei>(bufs.size()), bufs.data());
    if (glCheckNamedFramebufferStatus(coeff_fbo_.get(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw Unsupported(technique_ + " wavelet_bits=" + std::to_string(s_.bits) + ": the driver cannot render to " +
                        (half ? "16" : "32") + "-bit float targets (framebuffer incomplete)");
    bytes_ = s_.coeffs * s_.bits / 8 + 16;  // and the weighted colour pass's RGBA32F sum
  }

  WoitSettings s_;
  RenderTarget accum_;
  gl::Framebuffer coeff_fbo_;
  gl::Texture coeffs_;
  gl::Program coeff_pass_, blend_pass_, resolve_;
};

}  // namespace

std::unique_ptr<OitCase> make_woit_case(const ParamSet& p, CaseContext& ctx) {
  return std::make_unique<WoitCase>(p, ctx);
}

}  // namespace oitbench::oit
