#pragma once
// Each pixel's fragments of a frame, counted without storing one: what sizes a fragment pool before it
// is allocated (the exact techniques' pool sizing). The count program is the PPPA layout's count pass
// (shaders/capture/packed_arrays.glsl, STORAGE_PPPA_COUNT) built from the capture's own shaders, so it
// counts every fragment that reaches store_fragment(), as a capture of either layout does. One pass of
// the geometry and a read-back of 4 bytes a pixel, where sizing by a capture takes a capture into a
// guessed pool, the re-render after it overflows and the read-back of every fragment.
#include <functional>
#include <vector>

#include "core/registry.hpp"
#include "gl/gl_objects.hpp"
#include "gl/shader.hpp"
#include "oit/capture/fragment_storage.hpp"

namespace oitbench::oit {

// What the counts say: each pixel's depth, the peak, the total and the depths that occur.
struct FragmentCounts {
  std::vector<unsigned> depth;  // per pixel, row-major from the bottom row
  unsigned peak_depth = 0;
  size_t total_fragments = 0;
  std::vector<unsigned> depths() const;  // the distinct non-zero depths, ascending
};

class FragmentCounter {
 public:
  // `stages`: the capture's shaders (a fragment shader that calls store_fragment()); `extra`: the
  // capture's other defines (the scene's geometry_defines()).
  FragmentCounter(const CaseContext& ctx, const std::vector<ShaderStage>& stages, FragFormat format,
                  const Defines& extra = {});
  // The count program, for the caller's uniforms (viewProj, the scene's bindings).
  GLuint program() const { return program_.get(); }
  // Counts the fragments `draw` makes with program() current; the caller sets the rest of the state
  // (the target, the depth test, the colour mask), as for a capture.
  FragmentCounts count(const std::function<void()>& draw) const;

 private:
  int width_, height_;
  gl::Program program_;
  gl::Texture counts_;
};

}  // namespace oitbench::oit
