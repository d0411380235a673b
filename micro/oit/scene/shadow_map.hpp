#pragma once
// The self-shadowing effect's opacity shadow map (issue #13; docs/effects.md#self-shadowing): the
// scene's primitives seen from its light, as in Sintorn & Assarsson 2008 and the hair poster.
//   shadow-sort  each primitive's depth slice in the light's view and the stable stream-split radix
//                sort of the lines experiment (shaders/lines/{slice_keys,split,emit_indices}.comp,
//                PRIMITIVE_VERTICES 2 or 3), so that each slice is one range of an element buffer
//   shadow-map   each slice's primitives drawn from the light into its layer of a 3D texture,
//                adding optical depth -log(1 - alpha) (Kim & Neumann 2001), then a prefix over the
//                layers: layer k holds what lies in front of slice k
// Any fragment shader built with defines() and bound with bind() reads it through
// shaders/shadow/transmittance.glsl (shaders/scene/shade.glsl applies it and the ambient floor).
// validate() checks it on the CPU: the sort against a stable CPU sort, the map against the CPU's
// own map from the same slices (every fragment seen from the light, captured once, untimed), and
// measures its error against the exact deep shadow map (every light fragment sorted, composited).
#include <glm/glm.hpp>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/registry.hpp"
#include "core/timer.hpp"
#include "gl/gl_objects.hpp"
#include "gl/shader.hpp"
#include "oit/scene/scene.hpp"

namespace oitbench::oit {

// The passes build() times, as their rows name them.
inline constexpr const char* kShadowSortPass = "shadow-sort";
inline constexpr const char* kShadowMapPass = "shadow-map";
// The fault that shifts every slice one layer back (fault=shadow-slice-off): the map check must fail.
inline constexpr const char* kShadowSliceOffFault = "shadow-slice-off";
// The GPU map may differ from the CPU's by this much per texel (float sums in another order):
// |gpu - cpu| <= kShadowMapTolerance * (1 + cpu), in optical depth.
inline constexpr double kShadowMapTolerance = 1e-3;

struct ShadowCheck {
  std::map<std::string, std::string> metrics;  // the shadow_* columns (micro/experiments/oit.cpp)
  std::vector<std::string> problems;           // empty when the map is valid
};

class OpacityShadowMap {
 public:
  // Every primitive of `mesh` casts a shadow (indices, then opaque_indices). `slices` >= 1,
  // `resolution` the map's width and height in texels.
  OpacityShadowMap(const CaseContext& ctx, const Mesh& mesh, const Light& light, int slices, int resolution);
  ~OpacityShadowMap();
  OpacityShadowMap(const OpacityShadowMap&) = delete;
  OpacityShadowMap& operator=(const OpacityShadowMap&) = delete;

  void build(PassTimer& timer);  // the two passes above
  void build();                  // the same, untimed (before a case's first capture)
  // For a program built with defines(): the map on its texture unit and the lookup's uniforms
  // (the light's view-projection, the sliced range, the ambient floor).
  void bind(GLuint program) const;
  static Defines defines() { return {{"SELF_SHADOWING", ""}}; }

  int slices() const { return slices_; }
  int resolution() const { return resolution_; }
  size_t bytes() const;  // GPU memory of the timed passes: the map; per set indices, keys, sort, elements, draws
  const glm::mat4& light_view_projection() const { return light_view_proj_; }

  // After a build(): the checks and the shadow_* metrics (untimed; captures from the light once).
  ShadowCheck validate();

 private:
  struct LightFragments;
  struct PrimitiveSet;  // one kind of primitive (triangles; lines to come) with its own sort
  void sort_primitives(PrimitiveSet& set);
  void draw_map();
  LightFragments& light_fragments();

  CaseContext ctx_;
  int slices_, resolution_, bits_ = 0;
  bool slice_off_;
  float ambient_;
  glm::mat4 light_view_proj_{1.0f};
  float near_ = 0, far_ = 1;  // light-view distances the slices divide
  gl::Buffer vertices_;
  std::vector<PrimitiveSet> sets_;
  gl::VertexArray vao_;
  gl::Texture map_;
  gl::Framebuffer fbo_;
  gl::Program accumulate_, prefix_;
  std::unique_ptr<LightFragments> light_;  // captured at the first validate()
};

// A case's self-shadowing: the map of the scene's light (parameters shadow_slices and
// shadow_resolution, micro/experiments/oit.cpp) when the scene declares "self-shadowing", else
// nullptr: a scene without it runs no shadow pass and its rows have no shadow columns.
std::unique_ptr<OpacityShadowMap> make_self_shadowing(const CaseContext& ctx, const SceneDesc& scene, const Mesh& mesh,
                                                      const ParamSet& p);
// What a program that shades scene fragments (shaders/scene/shade.glsl) is built with.
inline Defines shading_defines(const std::unique_ptr<OpacityShadowMap>& shadow) {
  return shadow ? OpacityShadowMap::defines() : Defines{};
}

}  // namespace oitbench::oit
