// The shared part of MBOIT's and STOCHASTIC's cases (captured_view.hpp).
#include "oit/moments/captured_view.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "oit/case_support.hpp"
#include "oit/reference/image_compare.hpp"
#include "oit/reference/image_io.hpp"
#include "oit/reference/visible_capture.hpp"
#include "oit/scene/coverage_estimate.hpp"
#include "oit/splats/splat_check.hpp"
#include "shaders/stochastic/bindings.h"

namespace oitbench::oit {

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
  const auto referencing = ctx.phase(Phase::Reference);  // the fragments the references composite
  v.ref = reference_view(*v.fx, v.view_proj, p, ctx);
  return v;
}

void require_depth_bounds(const CapturedView& view, const std::string& technique) {
  const Mesh& mesh = view.fx->mesh();
  if (mesh.vertices.empty() && !mesh.splats.empty())
    throw Unsupported(technique + " on splats: its depth warp is bounded by the mesh's vertices and scene '" +
                      view.scene->name + "' has only splats (not supported yet)");
}

bool record_coverage(const CapturedView& view, GLuint framebuffer, int width, int height, const gl::Program& program,
                     std::vector<CoverageFragment>& out) {
  const GLuint words = STOCHASTIC_CAPTURE_WORDS;
  GLuint capacity = static_cast<GLuint>(view.ref->host.nodes.size() * 2 + 1024);
  for (int attempt = 0; attempt < 2; ++attempt) {
    gl::Buffer buffer = gl::make_buffer();
    size_t bytes = sizeof(GLuint) * (1 + static_cast<size_t>(capacity) * words);
    glNamedBufferStorage(buffer.get(), static_cast<GLsizeiptr>(bytes), nullptr, GL_DYNAMIC_STORAGE_BIT);
    glClearNamedBufferData(buffer.get(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glViewport(0, 0, width, height);
    glEnable(GL_MULTISAMPLE);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glProgramUniform1ui(program.get(), glGetUniformLocation(program.get(), "capacity"), capacity);
    glProgramUniform1i(program.get(), glGetUniformLocation(program.get(), "width"), width);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, STOCHASTIC_CAPTURE_BINDING, buffer.get());
    view.fx->bind_geometry(program.get());
    glUseProgram(program.get());
    view.mesh->draw();
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    GLuint count = 0;
    glGetNamedBufferSubData(buffer.get(), 0, sizeof(GLuint), &count);
    if (count > capacity) {
      capacity = count;
      continue;
    }
    std::vector<GLuint> data(static_cast<size_t>(count) * words);
    if (count) glGetNamedBufferSubData(buffer.get(), sizeof(GLuint), sizeof(GLuint) * data.size(), data.data());
    out.clear();
    for (size_t i = 0; i < count; ++i) {
      const GLuint* w = &data[i * words];
      // The opaque effect: the CPU hides what lies behind the opaque depth (the record keeps all).
      if (view.ref->backdrop.hides(w[0], std::bit_cast<float>(w[4]))) continue;
      // gl_FragDepth is clamped to the depth range: the centre depth of a fragment whose centre lies
      // outside its primitive is extrapolated and can leave [0, 1].
      out.push_back({w[0], w[1], w[2], w[3], std::clamp(std::bit_cast<float>(w[4]), 0.0f, 1.0f)});
    }
    return true;
  }
  return false;
}

CapturedViewCase::CapturedViewCase(const ParamSet& p, CaseContext& ctx)
    : width_(ctx.width()),
      height_(ctx.height()),
      technique_(p.get("technique")),
      view_(capture_view(p, ctx)),
      out_(ctx.width(), ctx.height(), GL_RGBA32F),
      flicker_runs_(static_cast<int>(p.get_int("flicker_runs"))),
      dump_(ctx.image_stem()) {
  phases_ = ctx.phase_clock();
}

void CapturedViewCase::set_view_projection(const glm::mat4& view_proj) {
  view_.fx->set_view_projection(view_proj);
  for (const gl::Program* prog : projected_) set_view_proj(*prog, view_proj);
}

bool CapturedViewCase::begin_run(PassTimer& timer, std::initializer_list<const gl::Program*> drawing) {
  view_.fx->run_before(timer);
  if (!view_.fx->transparency()) {
    view_.fx->fill_with_backdrop(out_.framebuffer(), out_.color_texture());  // nothing transparent
    return false;
  }
  for (const gl::Program* prog : drawing) view_.fx->bind_geometry(prog->get());
  view_.fx->bind_opaque_depth_sampler();
  return true;
}

void CapturedViewCase::keep_frame() {
  if (flicker_runs_ <= 0) return;
  frames_.push_back(rgb_of(out_.read_rgba32f()));
  if (static_cast<int>(frames_.size()) > flicker_runs_) frames_.erase(frames_.begin());
}

void CapturedViewCase::resolve_pass(PassTimer& timer, const gl::Program& resolve,
                                    const std::function<void()>& bind_inputs) {
  {
    auto t = timer.pass("resolve");
    out_.bind();
    bind_inputs();
    view_.fx->bind_backdrop(resolve.get());
    glUseProgram(resolve.get());
    quad_.draw();
  }
  keep_frame();
}

CapturedViewCase::ModelValidation CapturedViewCase::validate_against(
    const std::function<std::vector<double>()>& compute_model, double tolerance) {
  auto modelling = PhaseClock::Scope(phases_, Phase::Reference);
  const std::vector<double> model = compute_model();
  modelling.end();
  ModelValidation mv;
  auto& m = mv.v.metrics;
  auto reading = PhaseClock::Scope(phases_, Phase::Readback);
  mv.rgb = rgb_of(out_.read_rgba32f());
  reading.end();
  mv.stats = view_.ref->stats;
  const std::vector<double>& ref = view_.ref->composite;
  ApproxError err = approx_error(mv.rgb, ref);
  m["total_fragments"] = std::to_string(mv.stats.total_fragments);
  m["peak_depth"] = std::to_string(mv.stats.peak_depth);
  m["mean_depth"] = fmt(mv.stats.mean_depth);
  m["polygons"] = std::to_string(view_.fx->mesh().polygons());
  if (view_.fx->opaque()) m["hidden_fragments"] = std::to_string(view_.ref->hidden);
  m["rmse"] = fmt(err.rmse);
  m["psnr"] = fmt(err.psnr);
  m["max_abs_error"] = fmt(err.max_abs_error);
  m["frac_pixels_off"] = fmt(err.frac_pixels_off);
  m["model_rmse"] = fmt(approx_error(std::vector<float>(model.begin(), model.end()), ref).rmse);
  m["bytes_per_pixel"] = std::to_string(bytes_);
  mv.check = check_against_model(mv.rgb, model, width_, tolerance);
  m["nonfinite"] = std::to_string(mv.check.nonfinite);
  m["model_max_diff"] = fmt(mv.check.max_diff);
  if (frames_.size() >= 2) {
    Flicker f = flicker_of(frames_);
    m["flicker"] = fmt(f.mean);
    m["flicker_max"] = fmt(f.peak);
    m["flicker_pixels"] = std::to_string(f.changed);
  }
  if (!dump_.empty()) write_result_images(dump_, mv.rgb, ref, width_, height_);
  // Splat scenes: the error against the analytic reference, reported (an approximation is not held to it).
  auto splat_referencing = PhaseClock::Scope(phases_, Phase::Reference);
  report_splat_check(check_against_splats(*view_.fx, mv.rgb, 3, width_, height_, tolerance), tolerance, m, nullptr);
  splat_referencing.end();
  merge_shadow_check(m, mv.problems, view_.fx->validate_shadow());
  if (!mv.stats.error.empty()) mv.problems.push_back(mv.stats.error);
  return mv;
}

Validation CapturedViewCase::conclude_against(ModelValidation& mv, double tolerance, size_t allowed,
                                              const std::string& same) const {
  if (mv.check.nonfinite)
    mv.problems.push_back(std::to_string(mv.check.nonfinite) + " non-finite channel value(s) (NaN or Inf)");
  if (mv.check.out_of_range)
    mv.problems.push_back(std::to_string(mv.check.out_of_range) + " channel value(s) outside [0, 1]");
  if (mv.check.off > allowed) {
    std::string problem = std::to_string(mv.check.off) + " channel value(s) differ from " + technique_ +
                          "'s CPU model" + same + " by more than " + std::to_string(std::lround(tolerance * 255.0)) +
                          "/255";
    if (allowed) problem += " (" + std::to_string(allowed) + " allowed)";
    mv.problems.push_back(problem + "; first: " + mv.check.first_off);
  }
  conclude(mv.v, mv.problems);
  return mv.v;
}

}  // namespace oitbench::oit
