#pragma once
// Puts a case's result on the window: the RGBA32F image where alpha > 0, the scene's background
// where alpha == 0 (no fragment landed), scaled to the framebuffer; and saves what the window shows.
#include <glm/glm.hpp>
#include <string>

#include "gl/gl_objects.hpp"
#include "gl/render_target.hpp"
#include "gl/shader.hpp"

namespace oitbench::viewer {

class ImagePresenter {
 public:
  explicit ImagePresenter(const ShaderLibrary& shaders);
  // Draws `image` (image_width x image_height) over the bound framebuffer's viewport.
  // `opaque`: the opaque effect's colour (same size as `image`), or 0 for the constant background.
  void draw(GLuint image, int image_width, int image_height, glm::vec3 background, int fb_width, int fb_height,
            GLuint opaque = 0) const;

 private:
  gl::Program program_;
  FullscreenTriangle triangle_;
};

// Writes the default framebuffer's back buffer (what the next swap shows) as an 8-bit RGB PNG.
void write_window_png(const std::string& path, int fb_width, int fb_height);

}  // namespace oitbench::viewer
