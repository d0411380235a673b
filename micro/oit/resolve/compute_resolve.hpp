#pragma once
// The exact-OIT resolve as a compute pass (CS-IS, CS-IMS, CS-RBS-L: the GLSL-compute stand-in for
// Knowles 2014's CUDA rows): shaders/resolve/resolve.comp, one invocation per pixel in groups of
// group_x x group_y, storing the composited colour straight into the target's colour texture in
// the fragment-shader resolve's convention (rgb over the background, alpha 1 where resolved).
#include <glm/glm.hpp>
#include <string>

#include "core/registry.hpp"
#include "gl/render_target.hpp"
#include "oit/capture/fragment_storage.hpp"
#include "shaders/resolve/bindings.h"

namespace oitbench::oit {

// Image unit of the resolved colour (units 0-3 are the fragment storage's, see fragment_storage.hpp).
inline constexpr GLuint kResolvedUnit = OIT_RESOLVED_IMAGE_UNIT;

class ComputeResolve {
 public:
  // `defines`: the sort's and the storage layout's.
  ComputeResolve(const CaseContext& ctx, Defines defines, glm::vec3 background, int group_x, int group_y);
  // Clears `target`'s colour, resolves every pixel of `lists` into it and waits for nothing: the
  // caller's glFinish or read-back does (the barrier makes the stores visible to both).
  void run(const FragmentStorage& lists, const RenderTarget& target) const;
  GLuint program() const { return program_.get(); }

 private:
  gl::Program program_;
  int group_x_, group_y_;
};

// "8x1" -> {8, 1}; throws std::invalid_argument on anything else.
std::pair<int, int> parse_group(const std::string& text);

}  // namespace oitbench::oit
