#pragma once
// Gaussian splats on the GPU: the splat list as shaders/splats/splats.glsl reads it (SPLAT_WORDS vec4s a
// splat, shaders/splats/bindings.h), drawn as one instanced quad a splat through the splat path of
// shaders/scene/scene.vert (the SPLATS define). Every technique's geometry pass draws splats this way
// (GpuMesh::draw), with nothing of its own: the fragment it starts from (shaders/scene/fragment.glsl)
// is the Gaussian at the pixel centre with the depth key the splat_depth parameter selects.
#include <string>

#include "core/params.hpp"
#include "gl/gl_objects.hpp"
#include "gl/shader.hpp"
#include "oit/scene/scene.hpp"
#include "oit/splats/splat.hpp"

namespace oitbench::oit {

class GpuSplats {
 public:
  explicit GpuSplats(const SplatList& splats);
  size_t size() const { return count_; }
  // Every splat, instance i drawing splat i (submission order); the program is built with splat_defines().
  void draw() const;
  // Instance i draws splat order[i] (`order`: size() uints, the global sort's); the program is built with
  // splat_defines() plus SPLAT_ORDERED.
  void draw_ordered(GLuint order) const;
  GLuint buffer() const { return splats_.get(); }
  size_t bytes() const;

 private:
  gl::Buffer splats_;
  gl::VertexArray vao_;  // no attributes: the vertex stage reads the splat buffer
  size_t count_;
};

// The `splat_depth` parameter: a splat fragment's depth key, centre (3DGS) or ray-max (StopThePop);
// it applies only to cases whose scene holds splats.
ParamSpec splat_depth_param();
// Whether a scene's objects are splats (generators "splats" and "ply").
bool scene_has_splats(const SceneDesc& scene);
// SPLATS and, for splat_depth=ray-max, SPLAT_DEPTH_RAY_MAX. Throws std::invalid_argument for another value.
Defines splat_defines(const std::string& splat_depth);
// The splat rasteriser's viewport uniform (pixels) for a program built with splat_defines().
void bind_splat_viewport(GLuint program, int width, int height);

}  // namespace oitbench::oit
