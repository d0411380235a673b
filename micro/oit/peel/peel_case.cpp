// The oit experiment's case for DP and DDP (peel.hpp): captures the view's fragments once for the
// exact reference and the CPU model, then times the peel (two geometry passes per iteration, see
// shaders/peel/peel.frag) and the composite.
#include <algorithm>
#include <bit>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/parallel_rows.hpp"
#include "gl/render_target.hpp"
#include "oit/case_support.hpp"
#include "oit/peel/peel.hpp"
#include "oit/reference/image_compare.hpp"
#include "oit/reference/image_io.hpp"
#include "oit/reference/reference.hpp"
#include "oit/reference/visible_capture.hpp"
#include "oit/scene/coverage_estimate.hpp"
#include "oit/scene/gpu_mesh.hpp"
#include "oit/scene/scene.hpp"
#include "oit/scene/scene_passes.hpp"
#include "oit/splats/splat_check.hpp"
#include "oit/techniques.hpp"
#include "shaders/peel/bindings.h"

namespace oitbench::oit {

namespace {

// As the exact resolves: RGBA8 fragments for both sides, float blending against double.
constexpr double kTolerance = 2.0 / 255.0;
// max_layers=0 peels until the query finds nothing; this bounds a runaway loop all the same.
constexpr unsigned kIterationCap = 1u << 20;

glm::dvec4 unpack(unsigned c) {
  return {(c & 0xffu) / 255.0, ((c >> 8) & 0xffu) / 255.0, ((c >> 16) & 0xffu) / 255.0, (c >> 24) / 255.0};
}

}  // namespace

std::vector<ParamSpec> peel_params() {
  std::vector<ParamSpec> ps = {
      ParamSpec::integer("max_layers",
                         "layers peeled at most (rounded up to even where an iteration peels two, dual peeling); 0 "
                         "peels until the occlusion query finds no fragment left (exact)",
                         0, 65536, {"0"}),
      ParamSpec::choice(
          "tie_rule",
          "what orders fragments of equal depth: depth-colour peels (depth, RGBA8 colour) pairs, the exact "
          "composite's order; depth is classic peeling by depth alone, which loses all but one fragment of each depth",
          {"depth-colour", "depth"}, {"depth-colour"}),
  };
  return ps;
}

std::vector<PeelLayer> peel_layers(const HostLists& l, size_t pixel, bool depth_only) {
  std::vector<PeelLayer> f;
  for (unsigned n = l.heads[pixel]; n != kListEnd && n < l.nodes.size() && f.size() <= l.nodes.size(); n = l.next[n])
    f.push_back({std::bit_cast<float>(l.nodes[n].y), l.nodes[n].x, 1});
  std::sort(f.begin(), f.end(), [](const PeelLayer& a, const PeelLayer& b) {
    return a.depth != b.depth ? a.depth < b.depth : a.colour < b.colour;
  });
  std::vector<PeelLayer> layers;
  for (const auto& x : f) {
    if (!layers.empty() && layers.back().depth == x.depth) {
      if (layers.back().colour == x.colour)
        ++layers.back().count;
      else if (!depth_only)
        layers.push_back(x);
      // depth only: a second colour at a peeled depth is never peeled (lost)
    } else {
      layers.push_back(x);
    }
  }
  return layers;
}

std::vector<double> peel_model(const HostLists& l, const Backdrop& backdrop, const PeelSettings& s) {
  size_t pixels = l.heads.size();
  std::vector<double> out(pixels * 3);
  // Pixels are independent: their rows on every core (outside the timed regions).
  parallel_rows(pixels, static_cast<size_t>(std::max(1, l.width)), 0, [&](unsigned, size_t p) {
    std::vector<PeelLayer> layers = peel_layers(l, p, s.depth_only);
    size_t per = s.dual ? 2 : 1;
    if (layers.size() > per * s.iterations) {  // stopped early: the first (DDP: and last) iterations' layers
      std::vector<PeelLayer> kept(layers.begin(), layers.begin() + s.iterations);
      if (s.dual) kept.insert(kept.end(), layers.end() - s.iterations, layers.end());
      layers = kept;
    }
    glm::dvec3 c(0.0);
    double t = 1.0;
    for (const auto& x : layers) {
      glm::dvec4 k = unpack(x.colour);
      for (unsigned i = 0; i < x.count; ++i) {
        c += t * k.a * glm::dvec3(k);
        t *= 1.0 - k.a;
      }
    }
    c += t * glm::dvec3(backdrop.at(p));
    for (int k = 0; k < 3; ++k) out[p * 3 + k] = c[k];
  });
  return out;
}

namespace {

class PeelCase final : public OitCase {
 public:
  PeelCase(const ParamSet& p, CaseContext& ctx)
      : width_(ctx.width()),
        height_(ctx.height()),
        fx_(p, ctx),
        scene_(fx_.scene()),
        out_(ctx.width(), ctx.height(), GL_RGBA32F),
        dump_(ctx.image_stem()) {
    phases_ = ctx.phase_clock();
    settings_.dual = technique(p.get("technique")).variant == static_cast<int>(PeelKind::Dual);
    settings_.depth_only = p.get("tie_rule") == "depth";
    unsigned max_layers = static_cast<unsigned>(p.get_int("max_layers"));
    max_iterations_ = max_layers == 0 ? kIterationCap : (settings_.dual ? (max_layers + 1) / 2 : max_layers);

    glm::mat4 vp = fx_.view_projection();

    // The fragments, once per run and view (visible_capture.hpp: shared with the run's other cases that see
    // them): the exact reference and the model work on these. With the opaque effect: every transparent
    // fragment, hidden by the CPU against the opaque pass's depth.
    {
      const auto referencing = ctx.phase(Phase::Reference);
      ref_ = reference_view(fx_, vp, p, ctx);
    }

    Defines d = fx_.geometry_defines();
    for (auto& x : fx_.depth_sampler_defines()) d.push_back(x);
    if (settings_.dual) d.push_back({"DUAL", ""});
    if (settings_.depth_only) d.push_back({"TIE_RULE_DEPTH", ""});
    peel_ = ctx.build({{GL_VERTEX_SHADER, "scene/scene.vert"}, {GL_FRAGMENT_SHADER, "peel/peel.frag"}}, d);
    set_view_proj(peel_, vp);
    resolve_ = ctx.build({{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "peel/resolve.frag"}}, d);
    pass_uniform_ = glGetUniformLocation(peel_.get(), "peelPass");

    auto texture = [&](GLenum format) {
      gl::Texture t = gl::make_texture(GL_TEXTURE_2D);
      glTextureStorage2D(t.get(), 1, format, width_, height_);
      bytes_per_pixel_ += format == GL_RGBA32F ? 16 : format == GL_RG32F ? 8 : 4;
      return t;
    };
    front_accum_ = texture(GL_RGBA32F);
    if (settings_.dual) back_accum_ = texture(GL_RGBA32F);
    for (int i = 0; i < 2; ++i) {
      minmax_[i] = texture(GL_RG32F);
      front_key_[i] = texture(GL_R32UI);
      if (settings_.dual) back_key_[i] = texture(GL_R32UI);
    }
    peel_fbo_ = gl::make_framebuffer();
    glNamedFramebufferTexture(peel_fbo_.get(), GL_COLOR_ATTACHMENT0, front_accum_.get(), 0);
    if (settings_.dual) glNamedFramebufferTexture(peel_fbo_.get(), GL_COLOR_ATTACHMENT1, back_accum_.get(), 0);
    // The tie pass samples the min-max target just drawn, so it draws into a framebuffer without it.
    tie_fbo_ = gl::make_framebuffer();
    glNamedFramebufferParameteri(tie_fbo_.get(), GL_FRAMEBUFFER_DEFAULT_WIDTH, width_);
    glNamedFramebufferParameteri(tie_fbo_.get(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, height_);
    query_ = gl::make_query(GL_SAMPLES_PASSED);
  }

  void set_view_projection(const glm::mat4& view_proj) override {
    fx_.set_view_projection(view_proj);
    set_view_proj(peel_, view_proj);
  }
  GLuint opaque_texture() const override { return fx_.opaque_texture(); }
  std::map<std::string, std::string> resolved_params() const override { return fx_.resolved_params(); }
  GLuint result_texture() override { return out_.color_texture(); }

  void run(PassTimer& timer) override {
    fx_.run_before(timer);
    if (!fx_.transparency()) {  // nothing transparent: the image is the backdrop
      fx_.fill_with_backdrop(out_.framebuffer(), out_.color_texture());
      complete_ = true;
      return;
    }
    fx_.bind_geometry(peel_.get());
    fx_.bind_opaque_depth_sampler();
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    const GLenum minmax_attachment = settings_.dual ? GL_COLOR_ATTACHMENT2 : GL_COLOR_ATTACHMENT1;
    {
      auto t = timer.pass("peel");
      const float front_clear[4] = {0, 0, 0, 1}, zero[4] = {0, 0, 0, 0};
      glClearTexImage(front_accum_.get(), 0, GL_RGBA, GL_FLOAT, front_clear);
      if (settings_.dual) glClearTexImage(back_accum_.get(), 0, GL_RGBA, GL_FLOAT, zero);
      // Before the first layer: a front at depth -1 and a back at depth 2 enclose every fragment.
      const float outside[2] = {1.0f, 2.0f}, none[2] = {-2.0f, -2.0f};
      const unsigned key_zero = 0, key_max = 0xFFFFFFFFu;
      int prev = 0;
      glClearTexImage(minmax_[prev].get(), 0, GL_RG, GL_FLOAT, outside);
      glClearTexImage(front_key_[prev].get(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &key_zero);
      if (settings_.dual) glClearTexImage(back_key_[prev].get(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &key_zero);
      glUseProgram(peel_.get());
      iterations_ = 0;
      passes_ = 0;
      complete_ = false;
      for (;;) {
        int next = 1 - prev;
        // Peel: blend the layers found last time, find the depths of the next ones.
        glNamedFramebufferTexture(peel_fbo_.get(), minmax_attachment, minmax_[next].get(), 0);
        const GLenum bufs[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
        glNamedFramebufferDrawBuffers(peel_fbo_.get(), settings_.dual ? 3 : 2, bufs);
        glClearTexImage(minmax_[next].get(), 0, GL_RG, GL_FLOAT, none);
        glBindFramebuffer(GL_FRAMEBUFFER, peel_fbo_.get());
        glViewport(0, 0, width_, height_);
        glEnable(GL_BLEND);
        glBlendEquationi(0, GL_FUNC_ADD);
        glBlendFuncSeparatei(0, GL_DST_ALPHA, GL_ONE, GL_ZERO, GL_ONE_MINUS_SRC_ALPHA);  // under
        if (settings_.dual) {
          glBlendEquationi(1, GL_FUNC_ADD);
          glBlendFunci(1, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);  // over
        }
        glBlendEquationi(settings_.dual ? 2 : 1, GL_MAX);
        bind_state(prev, next);
        glUniform1i(pass_uniform_, 0);
        fx_.transparent().draw();
        ++passes_;
        glDisable(GL_BLEND);
        glBlendEquation(GL_FUNC_ADD);  // every draw buffer back to GL's default: later passes set only funcs
        glBlendFunc(GL_ONE, GL_ZERO);
        // Tie: the colour keys of the new layers; the query counts their fragments.
        glClearTexImage(front_key_[next].get(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &key_max);
        if (settings_.dual)
          glClearTexImage(back_key_[next].get(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT,
                          settings_.depth_only ? &key_max : &key_zero);
        glBindFramebuffer(GL_FRAMEBUFFER, tie_fbo_.get());
        glBindTextureUnit(PEEL_NEXT_MINMAX_UNIT, minmax_[next].get());
        glUniform1i(pass_uniform_, 1);
        glBeginQuery(GL_SAMPLES_PASSED, query_.get());
        fx_.transparent().draw();
        glEndQuery(GL_SAMPLES_PASSED);
        ++passes_;
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
        GLuint64 found = 0;
        glGetQueryObjectui64v(query_.get(), GL_QUERY_RESULT, &found);
        if (found == 0) {
          complete_ = true;
          break;
        }
        if (iterations_ == max_iterations_) break;  // layers are left: an approximation
        ++iterations_;
        prev = next;
      }
    }
    auto t = timer.pass("resolve");
    out_.bind();
    glBindTextureUnit(PEEL_FRONT_ACCUM_UNIT, front_accum_.get());
    if (settings_.dual) glBindTextureUnit(PEEL_BACK_ACCUM_UNIT, back_accum_.get());
    fx_.bind_backdrop(resolve_.get());
    glUseProgram(resolve_.get());
    quad_.draw();
  }

  Validation validate() override {
    Validation v;
    auto& m = v.metrics;
    auto reading = PhaseClock::Scope(phases_, Phase::Readback);
    std::vector<float> rgba = out_.read_rgba32f();
    reading.end();
    std::vector<float> rgb(rgba.size() / 4 * 3);
    for (size_t i = 0; i < rgba.size() / 4; ++i)
      for (int k = 0; k < 3; ++k) rgb[i * 3 + k] = rgba[i * 4 + k];
    const HostLists& host = ref_->host;
    const ListStats& stats = ref_->stats;
    const std::vector<double>& ref = ref_->composite;
    auto referencing = PhaseClock::Scope(phases_, Phase::Reference);
    PeelSettings s = settings_;
    s.iterations = iterations_;
    auto model = peel_model(host, ref_->backdrop, s);
    referencing.end();
    ApproxError err = approx_error(rgb, ref);
    size_t deepest = 0;  // the most layers in one pixel
    for (size_t px = 0; px < host.heads.size(); ++px)
      deepest = std::max(deepest, peel_layers(host, px, settings_.depth_only).size());
    size_t per = settings_.dual ? 2 : 1;
    m["polygons"] = std::to_string(fx_.mesh().polygons());
    if (fx_.opaque()) m["hidden_fragments"] = std::to_string(ref_->hidden);
    m["total_fragments"] = std::to_string(stats.total_fragments);
    m["peak_depth"] = std::to_string(stats.peak_depth);
    m["mean_depth"] = fmt(stats.mean_depth);
    m["tied_pixels"] = std::to_string(stats.tied_pixels);
    m["rmse"] = fmt(err.rmse);
    m["psnr"] = fmt(err.psnr);
    m["max_abs_error"] = fmt(err.max_abs_error);
    m["frac_pixels_off"] = fmt(err.frac_pixels_off);
    m["model_rmse"] = fmt(approx_error(std::vector<float>(model.begin(), model.end()), ref).rmse);
    m["layers_peeled"] = std::to_string(complete_ ? deepest : std::min(deepest, per * iterations_));
    m["peel_passes"] = std::to_string(passes_);
    m["peel_complete"] = complete_ ? "yes" : "no";
    m["bytes_per_pixel"] = std::to_string(bytes_per_pixel_);

    size_t nonfinite = 0, model_off = 0, exact_off = 0;
    double model_max = 0;
    std::string first_off, first_exact;
    for (size_t i = 0; i < rgb.size(); ++i) {
      if (!std::isfinite(rgb[i])) ++nonfinite;
      double d = std::abs(static_cast<double>(rgb[i]) - model[i]);
      if (!std::isfinite(d)) d = 1.0;
      model_max = std::max(model_max, d);
      if (d > kTolerance && model_off++ == 0) first_off = where(i, rgb[i], model[i]);
      double e = std::abs(static_cast<double>(rgb[i]) - ref[i]);
      if (!(e <= kTolerance) && exact_off++ == 0) first_exact = where(i, rgb[i], ref[i]);
    }
    m["nonfinite"] = std::to_string(nonfinite);
    m["model_max_diff"] = fmt(model_max);
    if (!dump_.empty()) write_result_images(dump_, rgb, ref, width_, height_);
    // Splat scenes: the error against the analytic reference, reported (held to the CPU models above).
    report_splat_check(check_against_splats(fx_, rgb, 3, width_, height_, kTolerance), kTolerance, m, nullptr);

    std::vector<std::string> problems;
    merge_shadow_check(m, problems, fx_.validate_shadow());
    if (!host.error.empty()) problems.push_back(host.error);
    if (!stats.error.empty()) problems.push_back(stats.error);
    if (nonfinite) problems.push_back(std::to_string(nonfinite) + " non-finite channel value(s) (NaN or Inf)");
    if (model_off)
      problems.push_back(std::to_string(model_off) +
                         " channel value(s) differ from the CPU model of the peeled layers by more than 2/255; "
                         "first: " +
                         first_off);
    if (complete_) {
      // Run to completion the peel must be the exact composite, and must have taken as many
      // iterations as the deepest pixel has layers.
      if (exact_off)
        problems.push_back(std::to_string(exact_off) +
                           " channel value(s) differ from the exact reference by more than 2/255 although every "
                           "layer was peeled; first: " +
                           first_exact);
      size_t expected = (deepest + per - 1) / per;
      if (iterations_ != expected)
        problems.push_back("the occlusion query ended the peel after " + std::to_string(iterations_) +
                           " iteration(s); the deepest pixel has " + std::to_string(deepest) + " layer(s), so " +
                           std::to_string(expected) + " were due");
    }
    conclude(v, problems);
    return v;
  }

 private:
  PhaseClock* phases_ = nullptr;  // the run's time account (core/phases.hpp); null: none
  std::string where(size_t i, double got, double want) const {
    size_t px = i / 3;
    return "pixel (" + std::to_string(px % width_) + "," + std::to_string(px / width_) + ") channel " +
           std::to_string(i % 3) + ": GPU " + fmt(got) + ", expected " + fmt(want);
  }
  void bind_state(int prev, int next) const {
    glBindTextureUnit(PEEL_PREV_MINMAX_UNIT, minmax_[prev].get());
    // The target being drawn is not bound for sampling (a feedback loop); the tie pass binds it.
    glBindTextureUnit(PEEL_NEXT_MINMAX_UNIT, minmax_[prev].get());
    glBindImageTexture(PEEL_PREV_FRONT_IMAGE, front_key_[prev].get(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);
    glBindImageTexture(PEEL_NEXT_FRONT_IMAGE, front_key_[next].get(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    if (settings_.dual) {
      glBindImageTexture(PEEL_PREV_BACK_IMAGE, back_key_[prev].get(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);
      glBindImageTexture(PEEL_NEXT_BACK_IMAGE, back_key_[next].get(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    }
  }
  static void set_view_proj(const gl::Program& prog, const glm::mat4& vp) {
    glProgramUniformMatrix4fv(prog.get(), glGetUniformLocation(prog.get(), "viewProj"), 1, GL_FALSE, &vp[0][0]);
  }

  int width_, height_;
  ScenePasses fx_;  // the scene's effects (scene_passes.hpp): the opaque pass, shading, the backdrop
  const SceneDesc& scene_;
  RenderTarget out_;
  FullscreenTriangle quad_;
  std::shared_ptr<const ReferenceView> ref_;  // the view's fragments, backdrop, statistics and exact composite
  PeelSettings settings_;
  unsigned max_iterations_ = 0, iterations_ = 0, passes_ = 0;
  bool complete_ = false;
  size_t bytes_per_pixel_ = 0;
  gl::Program peel_, resolve_;
  GLint pass_uniform_ = -1;
  gl::Texture front_accum_, back_accum_, minmax_[2], front_key_[2], back_key_[2];
  gl::Framebuffer peel_fbo_, tie_fbo_;
  gl::Query query_;
  std::string dump_;
};

}  // namespace

std::unique_ptr<OitCase> make_peel_case(const ParamSet& p, CaseContext& ctx) {
  return std::make_unique<PeelCase>(p, ctx);
}

}  // namespace oitbench::oit
