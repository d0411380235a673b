#include "oit/scene/scene_passes.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "oit/scene/coverage_estimate.hpp"
#include "shaders/scene/bindings.h"

namespace oitbench::oit {

namespace {

std::string list_text(const std::vector<std::string>& v, const char* sep = ", ") {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : sep) + x;
  return s;
}

}  // namespace

ParamSpec effects_param() {
  return {"effects",
          "the scene effects to simulate: scene (every effect the scene file declares) or a subset joined by '+' "
          "(" +
              list_text(effect_names(), ", ") +
              "), e.g. opaque+transparency; a comma list runs each set (effects=transparency,opaque+transparency)",
          {"scene"},
          {},
          {}};
}

std::string join_effects(const std::vector<std::string>& effects) { return list_text(effects, "+"); }

std::vector<std::string> select_effects(const SceneDesc& scene, const std::string& value) {
  if (value == "scene") return scene.effects;
  if (value.empty() || value.front() == '+' || value.back() == '+' || value.find("++") != std::string::npos)
    throw std::invalid_argument("effects=" + value + ": an empty effect name; valid effects: " +
                                list_text(effect_names()) + " (joined by '+', e.g. opaque+transparency), or scene");
  std::vector<std::string> asked;
  std::stringstream ss(value);
  std::string name;
  const auto& valid = effect_names();
  while (std::getline(ss, name, '+')) {
    if (std::find(valid.begin(), valid.end(), name) == valid.end())
      throw std::invalid_argument("effects=" + value + ": unknown effect '" + name +
                                  "'; valid effects: " + list_text(valid) + " (joined by '+'), or scene");
    if (!scene.has_effect(name))
      throw std::invalid_argument("effects=" + value + ": scene '" + scene.name + "' (" + scene.path +
                                  ") does not declare effect '" + name + "'; it declares: " + list_text(scene.effects));
    if (std::find(asked.begin(), asked.end(), name) == asked.end()) asked.push_back(name);
  }
  if (asked.empty()) throw std::invalid_argument("effects=" + value + ": no effect named");
  std::vector<std::string> out;
  for (const auto& v : valid)  // canonical order
    if (std::find(asked.begin(), asked.end(), v) != asked.end()) out.push_back(v);
  return out;
}

std::vector<std::string> effect_pass_names(const std::vector<std::string>& effects,
                                           const std::vector<std::string>& technique_passes) {
  auto has = [&](const char* e) { return std::find(effects.begin(), effects.end(), e) != effects.end(); };
  std::vector<std::string> passes;
  if (has("self-shadowing")) passes.insert(passes.end(), {"shadow-sort", "shadow-map"});
  if (has("opaque")) passes.push_back("opaque");
  if (has("transparency")) passes.insert(passes.end(), technique_passes.begin(), technique_passes.end());
  return passes;
}

namespace {

// What build_mesh() reads of the view: nothing where the view submits the primitives as generated and
// every generator ignores the view (planes, hairball, strands, models; smoke and splats read it), so the
// views of such a scene share one build (the engine grid's 12.76 M triangles: ~13 s each on llvmpipe);
// else the view, by name.
std::string view_key(const SceneDesc& scene, const View& view) {
  bool view_free = view.order == SubmitOrder::AsGenerated;
  for (const auto& o : scene.objects)
    view_free = view_free && (o.generator == "planes" || o.generator == "hairball" || o.generator == "strands" ||
                              o.generator == "model");
  return view_free ? "every view" : "view " + view.name;
}

// The geometry's cache key: everything build_mesh() reads (the scene file, its view where it reads it, the
// detail, whether opaque primitives are split off) and whether the transparent primitives are kept.
std::string geometry_key(const SceneDesc& scene, const View& view, Detail detail, bool opaque, bool transparency) {
  return "scene-geometry\n" + scene.path + "\n" + scene.name + "\n" + view_key(scene, view) + "\n" +
         (detail == Detail::Small ? "small" : "full") + (opaque ? "\nopaque" : "") +
         (transparency ? "" : "\nno transparency");
}

}  // namespace

std::shared_ptr<const SceneGeometry> scene_geometry(CaseContext& ctx, const SceneDesc& scene, const View& view,
                                                    Detail detail, bool opaque, bool transparency) {
  auto make = [&]() -> std::shared_ptr<const SceneGeometry> {
    auto g = std::make_shared<SceneGeometry>();
    if (transparency) {
      g->mesh = build_mesh(scene, view, detail, opaque);
    } else {  // the whole mesh (it casts shadows) without its transparent primitives, from the full one
      g->full = scene_geometry(ctx, scene, view, detail, opaque, true);
      g->mesh = g->full->mesh;
      g->mesh.indices.clear();
      g->mesh.line_indices.clear();
    }
    g->transparent = std::make_unique<GpuMesh>(g->mesh);
    if (opaque) g->opaque = std::make_unique<GpuMesh>(g->mesh, g->mesh.opaque_indices);
    return g;
  };
  if (!ctx.shared()) return make();
  return ctx.shared()->get<SceneGeometry>(geometry_key(scene, view, detail, opaque, transparency), make);
}

ScenePasses::ScenePasses(const ParamSet& p, CaseContext& ctx)
    : scene_(load_scene(p.get("scene"))),
      view_(scene_.view(p.get("view"))),
      width_(ctx.width()),
      height_(ctx.height()),
      skip_depth_test_(ctx.fault() == "no-opaque-depth") {
  try {
    effects_ = select_effects(scene_, p.has("effects") ? p.get("effects") : "scene");
  } catch (const std::invalid_argument& e) {
    throw SceneError(e.what());
  }
  const bool opaque = has("opaque");
  const Detail detail = p.get("detail") == "small" ? Detail::Small : Detail::Full;
  // A splat scene too large for the case's memory is refused from its splat count, before it is built
  // (10^7 splats are 2.5 GB while they build and upload).
  if (const double splats = scene_splat_count(scene_, detail); splats > 0)
    require_memory(
        splat_scene_memory(splats), ctx.memory(),
        "scene '" + scene_.name + "' (" + format_count(static_cast<unsigned long long>(splats)) + " splats):");
  // Built once per run for every case of this scene, view and effects (core/shared_cache.hpp).
  geometry_ = scene_geometry(ctx, scene_, view_, detail, opaque, has("transparency"));
  check_splats(p);
  // Every primitive casts its shadow, whatever else runs; built once now for the first capture.
  if (has("self-shadowing")) {
    shadow_ = make_self_shadowing(ctx, scene_, geometry_->full ? geometry_->full->mesh : geometry_->mesh, p);
    if (shadow_) shadow_->build();
  }
  view_proj_ = oit::view_projection(view_, geometry_->mesh, static_cast<float>(width_) / height_);
  if (opaque) {
    opaque_ = std::make_unique<Opaque>();
    opaque_->program =
        ctx.build({{GL_VERTEX_SHADER, "scene/scene.vert"}, {GL_FRAGMENT_SHADER, "scene/opaque.frag"}}, mesh_defines());
    opaque_->fbo = gl::make_framebuffer();
    opaque_->colour = gl::make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(opaque_->colour.get(), 1, GL_RGBA32F, width_, height_);
    opaque_->depth = gl::make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(opaque_->depth.get(), 1, GL_DEPTH32F_STENCIL8, width_, height_);
    glNamedFramebufferTexture(opaque_->fbo.get(), GL_COLOR_ATTACHMENT0, opaque_->colour.get(), 0);
    glNamedFramebufferTexture(opaque_->fbo.get(), GL_DEPTH_STENCIL_ATTACHMENT, opaque_->depth.get(), 0);
    if (glCheckNamedFramebufferStatus(opaque_->fbo.get(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw Unsupported("the opaque effect needs an RGBA32F + DEPTH32F_STENCIL8 framebuffer");
  }
  set_view_projection(view_proj_);
}

bool ScenePasses::has(const std::string& effect) const {
  return std::find(effects_.begin(), effects_.end(), effect) != effects_.end();
}

void ScenePasses::set_view_projection(const glm::mat4& view_proj) {
  view_proj_ = view_proj;
  if (opaque_)
    glProgramUniformMatrix4fv(opaque_->program.get(), glGetUniformLocation(opaque_->program.get(), "viewProj"), 1,
                              GL_FALSE, &view_proj_[0][0]);
}

void ScenePasses::run_before(PassTimer& timer) {
  if (shadow_) shadow_->build(timer);  // shadow-sort, shadow-map
  if (!opaque_) return;
  auto t = timer.pass("opaque");
  draw_opaque();
}

void ScenePasses::draw_opaque() {
  if (!opaque_) return;
  glBindFramebuffer(GL_FRAMEBUFFER, opaque_->fbo.get());
  glViewport(0, 0, width_, height_);
  const float bg[4] = {scene_.background.r, scene_.background.g, scene_.background.b, 0.0f};
  glClearNamedFramebufferfv(opaque_->fbo.get(), GL_COLOR, 0, bg);
  glClearNamedFramebufferfi(opaque_->fbo.get(), GL_DEPTH_STENCIL, 0, 1.0f, 0);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  bind_geometry(opaque_->program.get());
  glUseProgram(opaque_->program.get());
  geometry_->opaque->draw();
  glDisable(GL_DEPTH_TEST);
}

Defines ScenePasses::defines() const {
  if (!opaque_) return {};
  return {{"OPAQUE_BACKDROP", ""}};
}

void ScenePasses::bind_backdrop(GLuint program) const {
  glProgramUniform3f(program, glGetUniformLocation(program, "background"), scene_.background.r, scene_.background.g,
                     scene_.background.b);
  if (!opaque_) return;
  glBindTextureUnit(OIT_BACKDROP_UNIT, opaque_->colour.get());
}

Defines ScenePasses::mesh_defines() const {
  Defines d = shading_defines(shadow_);
  for (auto& x : defines()) d.push_back(x);
  return d;
}

Defines ScenePasses::geometry_defines() const {
  Defines d = mesh_defines();
  if (splats()) {
    for (auto& x : splat_defines(splat_depth_)) d.push_back(x);
  }
  return d;
}

void ScenePasses::bind_geometry(GLuint program) const {
  if (shadow_) shadow_->bind(program);
  if (splats()) bind_splat_viewport(program, width_, height_);
}

// Splats are drawn by their own vertex stage (shaders/splats/): a scene draws either splats or
// transparent triangles and segments, and its splats cast no shadow (the map draws triangles).
void ScenePasses::check_splats(const ParamSet& p) {
  if (!splats()) return;
  splat_depth_ = p.has("splat_depth") ? p.get("splat_depth") : "ray-max";
  const Mesh& m = geometry_->mesh;
  if (!m.indices.empty() || !m.line_indices.empty())
    throw Unsupported("scene '" + scene_.name + "' (" + scene_.path +
                      ") mixes splats with transparent triangles or segments: the splat rasteriser draws splats only");
  if (has("self-shadowing"))
    throw Unsupported("scene '" + scene_.name + "': splats cast no shadow (the shadow map draws triangles)");
}

ShadowCheck ScenePasses::validate_shadow() { return shadow_ ? shadow_->validate() : ShadowCheck{}; }

std::map<std::string, std::string> ScenePasses::resolved_params() const {
  std::map<std::string, std::string> r = {{"effects", join_effects(effects_)}};
  if (!shadow_) r["shadow_slices"] = r["shadow_resolution"] = "";
  if (!splats()) r["splat_depth"] = "";
  return r;
}

Defines ScenePasses::depth_sampler_defines() const {
  Defines d;  // what a program built with geometry_defines() adds for opaque_hides()
  if (opaque_ && !skip_depth_test_) d.push_back({"OPAQUE_DEPTH_SAMPLER", ""});  // the fault skips the test
  return d;
}

void ScenePasses::bind_opaque_depth_sampler() const {
  if (opaque_) glBindTextureUnit(OIT_OPAQUE_DEPTH_UNIT, opaque_->depth.get());
}

void ScenePasses::attach_opaque_depth(GLuint framebuffer) const {
  if (!opaque_) return;
  glNamedFramebufferRenderbuffer(framebuffer, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, 0);
  glNamedFramebufferTexture(framebuffer, GL_DEPTH_STENCIL_ATTACHMENT, opaque_->depth.get(), 0);
  if (glCheckNamedFramebufferStatus(framebuffer, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw Unsupported("the opaque effect: a technique's framebuffer with the opaque depth attached is incomplete");
}

void ScenePasses::begin_geometry() const {
  if (!opaque_ || skip_depth_test_) {
    glDisable(GL_DEPTH_TEST);
    return;
  }
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_FALSE);
}

void ScenePasses::end_geometry() const {
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
}

void ScenePasses::fill_with_backdrop(GLuint framebuffer, GLuint texture) const {
  if (!opaque_) {
    const float bg[4] = {scene_.background.r, scene_.background.g, scene_.background.b, 1.0f};
    glClearNamedFramebufferfv(framebuffer, GL_COLOR, 0, bg);
    return;
  }
  glCopyImageSubData(opaque_->colour.get(), GL_TEXTURE_2D, 0, 0, 0, 0, texture, GL_TEXTURE_2D, 0, 0, 0, 0, width_,
                     height_, 1);
}

Backdrop ScenePasses::read_backdrop() const {
  Backdrop b(scene_.background);
  if (!opaque_) return b;
  const size_t pixels = static_cast<size_t>(width_) * height_;
  std::vector<float> rgba(pixels * 4);
  glGetTextureImage(opaque_->colour.get(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(rgba.size() * sizeof(float)),
                    rgba.data());
  b.rgb.resize(pixels * 3);
  for (size_t p = 0; p < pixels; ++p)
    for (int k = 0; k < 3; ++k) b.rgb[p * 3 + k] = rgba[p * 4 + k];
  b.depth.resize(pixels);
  glGetTextureImage(opaque_->depth.get(), 0, GL_DEPTH_COMPONENT, GL_FLOAT,
                    static_cast<GLsizei>(b.depth.size() * sizeof(float)), b.depth.data());
  return b;
}

}  // namespace oitbench::oit
