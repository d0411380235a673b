#pragma once
// The viewer's false-colour depth complexity (Z): each pixel's captured fragments counted by
// walking its storage through the FRAG_* API (shaders/capture/), shown blue (1 fragment) ->
// green -> red (the peak) on a log scale, black where nothing landed. The same pass gives the
// overlay's fragment total and peak depth.
#include "gl/gl_objects.hpp"
#include "gl/render_target.hpp"
#include "gl/shader.hpp"

namespace oitbench::oit {
class FragmentStorage;
}

namespace oitbench::viewer {

class DepthComplexity {
 public:
  explicit DepthComplexity(const ShaderLibrary& shaders);

  struct Counts {
    unsigned peak = 0;
    unsigned long long total = 0;
  };
  // Counts the fragments `lists` holds (a width x height capture) and reads back peak and total.
  // `storage_defines` select the storage layout the count shader walks (compiled on first use).
  Counts count(const oit::FragmentStorage& lists, const Defines& storage_defines, int width, int height);
  // The last count in false colour over the bound framebuffer's viewport.
  void draw(int fb_width, int fb_height) const;

 private:
  const ShaderLibrary& shaders_;
  gl::Program count_, colour_;
  Defines count_defines_;
  gl::Texture counts_;
  gl::Buffer stats_;
  int width_ = 0, height_ = 0;
  FullscreenTriangle triangle_;
};

}  // namespace oitbench::viewer
