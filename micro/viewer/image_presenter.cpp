#include "viewer/image_presenter.hpp"

#include <vector>

#include "gl/gl.hpp"
#include "oit/reference/image_io.hpp"
#include "shaders/viewer/bindings.h"

namespace oitbench::viewer {

ImagePresenter::ImagePresenter(const ShaderLibrary& shaders)
    : program_(shaders.build(
          {{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "viewer/present.frag"}}, {})) {}

void ImagePresenter::draw(GLuint image, int image_width, int image_height, glm::vec3 background, int fb_width,
                          int fb_height, GLuint opaque) const {
  glUseProgram(program_.get());
  glUniform3f(glGetUniformLocation(program_.get(), "background"), background.r, background.g, background.b);
  glUniform2f(glGetUniformLocation(program_.get(), "texelsPerPixel"), static_cast<float>(image_width) / fb_width,
              static_cast<float>(image_height) / fb_height);
  glUniform1i(glGetUniformLocation(program_.get(), "hasOpaque"), opaque != 0);
  glBindTextureUnit(PRESENT_IMAGE_UNIT, image);
  glBindTextureUnit(PRESENT_OPAQUE_UNIT, opaque);
  triangle_.draw();
}

void write_window_png(const std::string& path, int fb_width, int fb_height) {
  std::vector<float> rgb(static_cast<size_t>(fb_width) * fb_height * 3);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, fb_width, fb_height, GL_RGB, GL_FLOAT, rgb.data());
  oit::write_png(path, rgb, fb_width, fb_height);
}

}  // namespace oitbench::viewer
