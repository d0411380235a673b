#include "oit/splats/gpu_splats.hpp"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "shaders/splats/bindings.h"

namespace oitbench::oit {

namespace {

// One splat as splats.glsl's load_splat reads it.
void pack(const Splat& s, float* w) {
  const float words[4 * SPLAT_WORDS] = {s.position.x, s.position.y, s.position.z, s.opacity,  //
                                        s.scale.x,    s.scale.y,    s.scale.z,    0.0f,       //
                                        s.rotation.w, s.rotation.x, s.rotation.y, s.rotation.z,
                                        s.colour.r,   s.colour.g,   s.colour.b,   0.0f};
  std::copy(std::begin(words), std::end(words), w);
}

}  // namespace

GpuSplats::GpuSplats(const SplatList& splats)
    : splats_(gl::make_buffer()), vao_(gl::make_vertex_array()), count_(splats.size()) {
  std::vector<float> words(std::max<size_t>(count_, 1) * 4 * SPLAT_WORDS, 0.0f);
  for (size_t i = 0; i < count_; ++i) pack(splats[i], &words[i * 4 * SPLAT_WORDS]);
  glNamedBufferStorage(splats_.get(), static_cast<GLsizeiptr>(words.size() * sizeof(float)), words.data(), 0);
}

size_t GpuSplats::bytes() const { return count_ * 4 * SPLAT_WORDS * sizeof(float); }

void GpuSplats::draw() const { draw_ordered(0); }

void GpuSplats::draw_ordered(GLuint order) const {
  if (count_ == 0) return;
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SPLATS_BINDING, splats_.get());
  if (order) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SPLAT_ORDER_BINDING, order);
  glBindVertexArray(vao_.get());
  glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(count_));
}

ParamSpec splat_depth_param() {
  ParamSpec p{"splat_depth",
              "splat scenes: a splat fragment's depth key, what every technique sorts, tests and weighs by: centre "
              "(the splat's mean's view depth, 3DGS, Kerbl et al. 2023) or ray-max (the depth of the Gaussian's "
              "maximum along the pixel's ray, StopThePop, Radl et al. 2024: the analytic reference's order)",
              {"ray-max"},
              {},
              {"ray-max", "centre"}};
  p.applies_if = [](const ParamSet& c) {
    if (!c.has("scene")) return true;
    try {
      return scene_has_splats(load_scene(c.get("scene")));
    } catch (const std::exception&) {
      return true;  // a scene that does not load is reported by the case (FILE:LINE:COLUMN)
    }
  };
  p.applies_if_text = "the case's scene holds splats";
  p.applies_if_reads = {"scene"};
  return p;
}

bool scene_has_splats(const SceneDesc& scene) {
  return std::any_of(scene.objects.begin(), scene.objects.end(),
                     [](const SceneObject& o) { return o.generator == "splats" || o.generator == "ply"; });
}

Defines splat_defines(const std::string& splat_depth) {
  if (splat_depth == "ray-max") return {{"SPLATS", ""}, {"SPLAT_DEPTH_RAY_MAX", ""}};
  if (splat_depth == "centre") return {{"SPLATS", ""}};
  throw std::invalid_argument("splat_depth=" + splat_depth + ": valid values are ray-max, centre");
}

void bind_splat_viewport(GLuint program, int width, int height) {
  glProgramUniform2f(program, glGetUniformLocation(program, "splatViewport"), static_cast<float>(width),
                     static_cast<float>(height));
}

}  // namespace oitbench::oit
