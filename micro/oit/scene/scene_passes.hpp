#pragma once
// The effects a case runs and the passes they contribute (docs/effects.md). A scene declares its
// effects (scenes/README.md); the `effects` parameter runs all of them ("scene") or a subset
// ("opaque+transparency"); every oit technique builds its frame from ScenePasses:
//   opaque          pass "opaque": the opaque primitives into colour and depth; the technique's
//                   geometry passes then test the transparent fragments against that depth
//                   (early fragment tests: a hidden fragment is never stored) and composite over
//                   that colour (shaders/scene/backdrop.glsl)
//   transparency    the technique's own passes (capture, resolve, ...); without it none run
//   self-shadowing  the shadow map's passes (micro/oit/scene/shadow_map.hpp)
// Without the opaque effect, opaque materials are captured like glass at alpha 1.
#include <glm/glm.hpp>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/registry.hpp"
#include "gl/gl_objects.hpp"
#include "gl/shader.hpp"
#include "oit/reference/reference.hpp"
#include "oit/scene/gpu_mesh.hpp"
#include "oit/scene/scene.hpp"
#include "oit/scene/shadow_map.hpp"

namespace oitbench::oit {

// The `effects` parameter: "scene" (every effect the scene declares) or effect names joined by '+'.
ParamSpec effects_param();
// The effects a value selects from a scene, in effect_names() order. Throws std::invalid_argument
// for an unknown name (listing the valid ones) or one the scene does not declare (naming its file).
std::vector<std::string> select_effects(const SceneDesc& scene, const std::string& value);
std::string join_effects(const std::vector<std::string>& effects);  // "opaque+transparency"

// The pass rows a frame of these effects has, in order, around the technique's own passes
// (`technique_passes`, e.g. {"capture", "resolve"}): what a case's rows must be, and nothing else.
std::vector<std::string> effect_pass_names(const std::vector<std::string>& effects,
                                           const std::vector<std::string>& technique_passes);

// One view of a scene as the cases draw it: the mesh (without its transparent primitives where the
// transparency effect is off) and its GPU copies. Immutable once built; shared by every case of a run
// that draws the same scene, view, detail and effects (CaseContext::shared()).
struct SceneGeometry {
  Mesh mesh;
  std::unique_ptr<GpuMesh> transparent;       // mesh.indices and mesh.line_indices
  std::unique_ptr<GpuMesh> opaque;            // mesh.opaque_indices (the opaque effect only)
  std::shared_ptr<const SceneGeometry> full;  // without transparency: the mesh it was cut from
};
// The run's shared geometry for this view (built on first use), or a new one where ctx shares nothing.
std::shared_ptr<const SceneGeometry> scene_geometry(CaseContext& ctx, const SceneDesc& scene, const View& view,
                                                    Detail detail, bool opaque, bool transparency);

class ScenePasses {
 public:
  // Loads the scene (p "scene", "view", "detail", "effects") and builds its meshes for the view.
  ScenePasses(const ParamSet& p, CaseContext& ctx);

  const SceneDesc& scene() const { return scene_; }
  const View& view() const { return view_; }
  const Mesh& mesh() const { return geometry_->mesh; }
  const GpuMesh& transparent() const { return *geometry_->transparent; }  // what the technique's geometry passes draw
  const std::vector<std::string>& effects() const { return effects_; }
  bool has(const std::string& effect) const;
  bool opaque() const { return opaque_ != nullptr; }
  bool transparency() const { return has("transparency"); }
  glm::mat4 view_projection() const { return view_proj_; }
  void set_view_projection(const glm::mat4& view_proj);

  // The effect passes that come before the technique's: "opaque" (and the shadow passes). Each
  // is a pass row of its own; nothing runs for an effect the case does not have.
  void run_before(PassTimer& timer);
  // The opaque pass's draw alone, untimed (a case's prepare: its reference capture needs the depth).
  void draw_opaque();

  // For every technique's shaders (shaders/scene/backdrop.glsl): OPAQUE_BACKDROP with the opaque effect.
  Defines defines() const;
  // For the programs that draw the transparent primitives (shaders/scene/scene.vert, fragment.glsl):
  // SELF_SHADOWING with the self-shadowing effect, plus defines(); a scene of splats adds
  // splat_defines() (SPLATS, and the splat_depth key).
  Defines geometry_defines() const;
  // Before a geometry pass: the shadow map and its lookup's uniforms for `program` (a program
  // built with geometry_defines()), and the splat rasteriser's viewport.
  void bind_geometry(GLuint program) const;
  // The scene's splats on the GPU (null without any); transparent().draw() draws them.
  const GpuSplats* splats() const { return geometry_->transparent->splats(); }
  const std::string& splat_depth() const { return splat_depth_; }  // splat scenes: the splat_depth parameter
  // The self-shadowing checks and shadow_* metrics (micro/oit/scene/shadow_map.hpp); empty without it.
  ShadowCheck validate_shadow();
  bool self_shadowing() const { return shadow_ != nullptr; }
  // The parameters of effects that did not run, emptied for the rows (like a scoped parameter).
  std::map<std::string, std::string> resolved_params() const;
  // OPAQUE_DEPTH_SAMPLER (with the opaque effect): added to geometry_defines() by a technique whose
  // shaders call opaque_hides() (it cannot use the opaque depth buffer's own test).
  Defines depth_sampler_defines() const;
  // Sets `background` and binds the opaque colour at its unit (shaders/scene/bindings.h).
  void bind_backdrop(GLuint program) const;
  // Binds the opaque depth for opaque_hides() (never while it is attached to the bound framebuffer).
  void bind_opaque_depth_sampler() const;
  // Makes the opaque depth the depth-stencil attachment of `framebuffer` (no-op without the
  // effect), so that a technique's geometry passes can test against it.
  void attach_opaque_depth(GLuint framebuffer) const;
  // Before a geometry pass that draws the transparent primitives: the opaque depth test (less,
  // no depth writes) with the effect, no depth test without it. fault=no-opaque-depth skips it.
  void begin_geometry() const;
  void end_geometry() const;
  // The opaque colour as the image a technique without transparent work leaves: copies it into
  // `texture` (RGBA32F, the target's size), or clears it to the background without the effect.
  void fill_with_backdrop(GLuint framebuffer, GLuint texture) const;

  GLuint opaque_texture() const { return opaque_ ? opaque_->colour.get() : 0; }
  // The backdrop read back for the CPU references (the opaque colour and depth after run_before).
  Backdrop read_backdrop() const;

 private:
  SceneDesc scene_;
  View view_;
  std::vector<std::string> effects_;
  std::shared_ptr<const SceneGeometry> geometry_;
  glm::mat4 view_proj_{1.0f};
  int width_, height_;
  std::string splat_depth_;      // splat scenes: the splat_depth parameter
  Defines mesh_defines() const;  // geometry_defines() for the mesh path (the opaque pass)
  void check_splats(const ParamSet& p);
  bool skip_depth_test_;  // fault=no-opaque-depth

  struct Opaque {
    gl::Program program;
    gl::Framebuffer fbo;
    gl::Texture colour, depth;  // RGBA32F; DEPTH32F_STENCIL8 (float: the CPU compares the same values)
  };
  std::unique_ptr<Opaque> opaque_;
  std::unique_ptr<OpacityShadowMap> shadow_;  // the self-shadowing effect
};

}  // namespace oitbench::oit
