// The oit experiment's MBOIT case (moments.hpp): a moment pass, a weighted colour pass and a
// resolve (shaders/moments/), validated against mboit_model (moment_model.hpp).
#include <algorithm>
#include <glm/gtc/matrix_transform.hpp>
#include <sstream>

#include "gl/render_target.hpp"
#include "oit/case_support.hpp"
#include "oit/moments/moment_model.hpp"
#include "oit/moments/moments.hpp"
#include "oit/reference/image_compare.hpp"
#include "oit/reference/image_io.hpp"
#include "oit/reference/reference.hpp"
#include "oit/scene/coverage_estimate.hpp"
#include "shaders/moments/bindings.h"

namespace oitbench::oit {

namespace {

// The GPU reconstructs in float what the model reconstructs in double; the moments' Hankel and
// Toeplitz systems are ill-conditioned by design (the bias keeps them just positive definite), so
// a float solve can move a transmittance by a few 1/255 where the model's does not (measured on
// the shipped scenes at 128x128: docs/experiments/oit.md). The tolerance is per channel.
constexpr double kMomentTolerance = 4.0 / 255.0;

}  // namespace

std::vector<ParamSpec> moment_params() {
  std::vector<ParamSpec> ps = {
      {"moments",
       "MBOIT: real numbers stored beside the zeroth moment: power moments b1..bn, or n/2 complex "
       "trigonometric moments (the paper's 4, 6, 8 power and 2, 3, 4 trigonometric moments)",
       {"4"},
       {},
       {"4", "6", "8"}},
      {"moment_kind",
       "MBOIT: power moments of the log-warped depth, or trigonometric moments",
       {"power"},
       {},
       {"power", "trigonometric"}},
      {"moment_bits",
       "MBOIT: storage of the moments, 32-bit float targets or 16-bit float (RGBA16F) ones; the paper's bias "
       "for each",
       {"32"},
       {},
       {"32", "16"}},
      {"samples_per_pixel",
       "STOCHASTIC: coverage samples per pixel (MSAA samples times passes where the driver has fewer)",
       {"8"},
       {},
       {"4", "8", "16"}},
  };
  return ps;
}

CapturedView capture_view(const ParamSet& p, CaseContext& ctx) {
  CapturedView v;
  v.fx = std::make_unique<ScenePasses>(p, ctx);
  v.scene = &v.fx->scene();
  const View& view = v.fx->view();
  const Mesh& mesh = v.fx->mesh();
  v.mesh = &v.fx->transparent();
  v.view_proj = v.fx->view_projection();
  // The planes back out of the perspective matrix (glm::perspective's layout), as approx_case.cpp.
  glm::mat4 pm = v.view_proj * glm::inverse(glm::lookAt(view.eye, view.target, view.up));
  v.near_far = {pm[3][2] / (pm[2][2] - 1.0f), pm[3][2] / (pm[2][2] + 1.0f)};
  // The paper warps the view depth between bounds of the scene, not the projection's planes (whose
  // near plane can be far in front of the geometry): the vertices' own extent, slightly widened.
  glm::vec3 forward = glm::normalize(view.target - view.eye);
  float lo = 1e30f, hi = -1e30f;
  for (const auto& vertex : mesh.vertices) {
    float d = glm::dot(vertex.position - view.eye, forward);
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
  lo = std::clamp(lo * 0.999f, v.near_far.x, v.near_far.y);
  hi = std::clamp(hi * 1.001f, lo * 1.001f, v.near_far.y);
  v.depth_range = {lo, hi};
  size_t pixels = static_cast<size_t>(ctx.width()) * ctx.height();
  auto lists = make_fragment_storage(parse_capture_storage(p.get("capture")), ctx, pixels * 4, false, {},
                                     capture_budget(mesh, v.view_proj, ctx, v.fx->opaque() ? 2 : 1));
  auto capture = build_capture_programs(
      *lists, ctx, {{GL_VERTEX_SHADER, "oit/capture.vert"}, {GL_FRAGMENT_SHADER, "oit/capture.frag"}},
      v.fx->geometry_defines());
  for (const auto& prog : capture) {
    set_view_proj(prog, v.view_proj);
    v.fx->bind_geometry(prog.get());
  }
  const auto referencing = ctx.phase(Phase::Reference);  // the fragments the references composite
  v.fx->draw_opaque();
  v.backdrop = v.fx->read_backdrop();
  RenderTarget target(ctx.width(), ctx.height(), GL_R8);
  target.bind();
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  lists->capture(ids(capture), [&] { v.mesh->draw(); });
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  v.fragments = visible_fragments(lists->read_back(), v.backdrop, v.hidden);
  return v;
}

namespace {

class MboitCase final : public OitCase {
 public:
  MboitCase(const ParamSet& p, CaseContext& ctx)
      : width_(ctx.width()),
        height_(ctx.height()),
        view_(capture_view(p, ctx)),
        out_(ctx.width(), ctx.height(), GL_RGBA32F),
        accum_(ctx.width(), ctx.height(), GL_RGBA32F),
        flicker_runs_(static_cast<int>(p.get_int("flicker_runs"))),
        dump_(ctx.image_stem()) {
    phases_ = ctx.phase_clock();
    s_.kind = p.get("moment_kind") == "trigonometric" ? MomentKind::Trigonometric : MomentKind::Power;
    s_.moments = static_cast<int>(p.get_int("moments"));
    s_.bits = static_cast<int>(p.get_int("moment_bits"));
    s_.bias = mboit_paper_bias(s_.kind, s_.moments, s_.bits);
    s_.near_far = view_.near_far;
    s_.depth_range = view_.depth_range;

    // The moment targets: b0, b1..b4, and b5..b6 or b5..b8.
    const bool half = s_.bits == 16;
    const GLenum r = half ? GL_R16F : GL_R32F, rg = half ? GL_RG16F : GL_RG32F, rgba = half ? GL_RGBA16F : GL_RGBA32F;
    std::vector<GLenum> formats = {r, rgba};
    if (s_.moments == 6) formats.push_back(rg);
    if (s_.moments == 8) formats.push_back(rgba);
    moments_fbo_ = gl::make_framebuffer();
    for (size_t i = 0; i < formats.size(); ++i) {
      targets_.push_back(gl::make_texture(GL_TEXTURE_2D));
      glTextureStorage2D(targets_.back().get(), 1, formats[i], width_, height_);
      glNamedFramebufferTexture(moments_fbo_.get(), GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i),
                                targets_.back().get(), 0);
      bytes_ += (i == 0 ? 1 : formats[i] == rg ? 2 : 4) * (half ? 2 : 4);
    }
    std::vector<GLenum> bufs;
    for (size_t i = 0; i < formats.size(); ++i) bufs.push_back(GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i));
    glNamedFramebufferDrawBuffers(moments_fbo_.get(), static_cast<GLsizei>(bufs.size()), bufs.data());
    if (glCheckNamedFramebufferStatus(moments_fbo_.get(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw Unsupported("MBOIT moment_bits=" + std::to_string(s_.bits) + ": the driver cannot render to " +
                        (half ? "16" : "32") + "-bit float targets (framebuffer incomplete)");
    bytes_ += 16;  // the weighted colour pass's RGBA32F sum

    Defines d = view_.fx->geometry_defines();
    for (auto& x : view_.fx->depth_sampler_defines()) d.push_back(x);
    d.push_back({"MOMENT_COUNT", std::to_string(s_.moments)});
    if (s_.kind == MomentKind::Trigonometric) d.push_back({"MOMENT_TRIGONOMETRIC", ""});
    moment_pass_ = ctx.build({{GL_VERTEX_SHADER, "oit/capture.vert"}, {GL_FRAGMENT_SHADER, "moments/moments.frag"}}, d);
    blend_pass_ = ctx.build({{GL_VERTEX_SHADER, "oit/capture.vert"}, {GL_FRAGMENT_SHADER, "moments/blend.frag"}}, d);
    resolve_ =
        ctx.build({{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "moments/resolve.frag"}}, d);
    for (const gl::Program* prog : {&moment_pass_, &blend_pass_}) {
      set_view_proj(*prog, view_.view_proj);
      glProgramUniform2f(prog->get(), glGetUniformLocation(prog->get(), "nearFar"), s_.near_far.x, s_.near_far.y);
      glProgramUniform2f(prog->get(), glGetUniformLocation(prog->get(), "depthRange"), s_.depth_range.x,
                         s_.depth_range.y);
    }
    glProgramUniform1f(blend_pass_.get(), glGetUniformLocation(blend_pass_.get(), "momentBias"), s_.bias);
    glProgramUniform1f(blend_pass_.get(), glGetUniformLocation(blend_pass_.get(), "overestimation"), s_.overestimation);
  }

  void set_view_projection(const glm::mat4& view_proj) override {
    view_.fx->set_view_projection(view_proj);
    for (const gl::Program* prog : {&moment_pass_, &blend_pass_}) set_view_proj(*prog, view_proj);
  }
  GLuint result_texture() override { return out_.color_texture(); }
  GLuint opaque_texture() const override { return view_.fx->opaque_texture(); }
  std::map<std::string, std::string> resolved_params() const override { return view_.fx->resolved_params(); }

  void run(PassTimer& timer) override {
    view_.fx->run_before(timer);
    if (!view_.fx->transparency()) {  // nothing transparent: the image is the backdrop
      view_.fx->fill_with_backdrop(out_.framebuffer(), out_.color_texture());
      return;
    }
    for (const gl::Program* prog : {&moment_pass_, &blend_pass_}) view_.fx->bind_geometry(prog->get());
    view_.fx->bind_opaque_depth_sampler();
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    {
      auto t = timer.pass("moments");
      glBindFramebuffer(GL_FRAMEBUFFER, moments_fbo_.get());
      glViewport(0, 0, width_, height_);
      const float zero[4] = {0, 0, 0, 0};
      for (GLint i = 0; i < static_cast<GLint>(targets_.size()); ++i)
        glClearNamedFramebufferfv(moments_fbo_.get(), GL_COLOR, i, zero);
      glEnable(GL_BLEND);
      glBlendFunc(GL_ONE, GL_ONE);
      glUseProgram(moment_pass_.get());
      view_.mesh->draw();
    }
    {
      auto t = timer.pass("blend");
      accum_.bind();
      const float zero[4] = {0, 0, 0, 0};
      glClearNamedFramebufferfv(accum_.framebuffer(), GL_COLOR, 0, zero);
      glBlendFunc(GL_ONE, GL_ONE);
      bind_moments();
      glUseProgram(blend_pass_.get());
      view_.mesh->draw();
      glDisable(GL_BLEND);
    }
    {
      auto t = timer.pass("resolve");
      out_.bind();
      bind_moments();
      glBindTextureUnit(MOMENTS_ACCUM_UNIT, accum_.color_texture());
      view_.fx->bind_backdrop(resolve_.get());
      glUseProgram(resolve_.get());
      quad_.draw();
    }
    if (flicker_runs_ > 0) {  // outside the timed passes: the frames the flicker metric compares
      frames_.push_back(rgb_of(out_.read_rgba32f()));
      if (static_cast<int>(frames_.size()) > flicker_runs_) frames_.erase(frames_.begin());
    }
  }

  Validation validate() override {
    Validation v;
    auto& m = v.metrics;
    auto reading = PhaseClock::Scope(phases_, Phase::Readback);
    std::vector<float> rgb = rgb_of(out_.read_rgba32f());
    reading.end();
    const HostLists& host = view_.fragments;
    ListStats stats = list_stats(host);
    auto referencing = PhaseClock::Scope(phases_, Phase::Reference);
    auto ref = composite_reference(host, view_.backdrop);
    size_t rebiased = 0;
    std::vector<double> model = mboit_model(host, view_.backdrop, s_, &rebiased);
    referencing.end();
    ApproxError err = approx_error(rgb, ref);
    m["total_fragments"] = std::to_string(stats.total_fragments);
    m["peak_depth"] = std::to_string(stats.peak_depth);
    m["mean_depth"] = fmt(stats.mean_depth);
    m["polygons"] = std::to_string(view_.fx->mesh().polygons());
    if (view_.fx->opaque()) m["hidden_fragments"] = std::to_string(view_.hidden);
    m["rmse"] = fmt(err.rmse);
    m["psnr"] = fmt(err.psnr);
    m["max_abs_error"] = fmt(err.max_abs_error);
    m["frac_pixels_off"] = fmt(err.frac_pixels_off);
    m["model_rmse"] = fmt(approx_error(std::vector<float>(model.begin(), model.end()), ref).rmse);
    m["moment_bias"] = fmt(s_.bias);
    m["moment_rebiased"] = fmt(stats.total_fragments ? static_cast<double>(rebiased) / stats.total_fragments : 0.0);
    m["bytes_per_pixel"] = std::to_string(bytes_);
    ModelCheck check = check_against_model(rgb, model, width_, kMomentTolerance);
    m["nonfinite"] = std::to_string(check.nonfinite);
    m["model_max_diff"] = fmt(check.max_diff);
    m["model_off_channels"] = std::to_string(check.off);
    if (frames_.size() >= 2) {
      Flicker f = flicker_of(frames_);
      m["flicker"] = fmt(f.mean);
      m["flicker_max"] = fmt(f.peak);
      m["flicker_pixels"] = std::to_string(f.changed);
    }
    if (!dump_.empty()) write_result_images(dump_, rgb, ref, width_, height_);

    std::vector<std::string> problems;
    merge_shadow_check(m, problems, view_.fx->validate_shadow());
    if (!stats.error.empty()) problems.push_back(stats.error);
    if (check.nonfinite)
      problems.push_back(std::to_string(check.nonfinite) + " non-finite channel value(s) (NaN or Inf)");
    if (check.out_of_range) problems.push_back(std::to_string(check.out_of_range) + " channel value(s) outside [0, 1]");
    // The moment systems are ill-conditioned by design (the bias keeps them just positive
    // definite): where a pixel's moments sit at that edge the GPU's float solve and the model's
    // double one can part by more than the tolerance (measured: 0.3% of the channels of smoke with
    // 4 power moments in 32 bits), and with 16-bit sums they can disagree on raising the bias. Up
    // to 1% of the channels may differ; the wrong-result fault changes 12.5% of the pixels.
    const size_t allowed = rgb.size() / 100;
    if (check.off > allowed)
      problems.push_back(std::to_string(check.off) +
                         " channel value(s) differ from MBOIT's CPU model by more than 4/255 (" +
                         std::to_string(allowed) + " allowed); first: " + check.first_off);
    conclude(v, problems);
    return v;
  }

 private:
  PhaseClock* phases_ = nullptr;  // the run's time account (core/phases.hpp); null: none
  // The colour behind the transparent layers, in one place (the opaque effect will replace it).
  void bind_moments() const {
    for (size_t i = 0; i < targets_.size(); ++i)
      glBindTextureUnit(MOMENTS_B0_UNIT + static_cast<GLuint>(i), targets_[i].get());
  }

  int width_, height_;
  CapturedView view_;
  MboitSettings s_;
  RenderTarget out_, accum_;
  FullscreenTriangle quad_;
  gl::Framebuffer moments_fbo_;
  std::vector<gl::Texture> targets_;
  gl::Program moment_pass_, blend_pass_, resolve_;
  int bytes_ = 0;
  int flicker_runs_;
  std::string dump_;
  std::vector<std::vector<float>> frames_;
};

}  // namespace

std::unique_ptr<OitCase> make_mboit_case(const ParamSet& p, CaseContext& ctx) {
  return std::make_unique<MboitCase>(p, ctx);
}

}  // namespace oitbench::oit
