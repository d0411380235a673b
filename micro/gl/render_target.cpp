#include "gl/render_target.hpp"

#include <stdexcept>
#include <string>

namespace oitbench {

RenderTarget::RenderTarget(int width, int height, GLenum color_format, bool depth_stencil)
    : width_(width), height_(height), fbo_(gl::make_framebuffer()), color_(gl::make_texture(GL_TEXTURE_2D)) {
  glTextureStorage2D(color_.get(), 1, color_format, width, height);
  glNamedFramebufferTexture(fbo_.get(), GL_COLOR_ATTACHMENT0, color_.get(), 0);
  if (depth_stencil) {
    depth_stencil_ = gl::make_renderbuffer();
    glNamedRenderbufferStorage(depth_stencil_.get(), GL_DEPTH24_STENCIL8, width, height);
    glNamedFramebufferRenderbuffer(fbo_.get(), GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, depth_stencil_.get());
  }
  GLenum status = glCheckNamedFramebufferStatus(fbo_.get(), GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error("render target " + std::to_string(width) + "x" + std::to_string(height) +
                             " incomplete (status 0x" + std::to_string(status) + ")");
}

void RenderTarget::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
  glViewport(0, 0, width_, height_);
}

std::vector<float> RenderTarget::read_rgba32f() const {
  std::vector<float> px(static_cast<size_t>(width_) * static_cast<size_t>(height_) * 4);
  glGetTextureImage(color_.get(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(px.size() * sizeof(float)), px.data());
  return px;
}

std::vector<unsigned> RenderTarget::read_r32ui() const {
  std::vector<unsigned> px(static_cast<size_t>(width_) * static_cast<size_t>(height_));
  glGetTextureImage(color_.get(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT,
                    static_cast<GLsizei>(px.size() * sizeof(unsigned)), px.data());
  return px;
}

void FullscreenTriangle::draw(GLsizei instances) const {
  glBindVertexArray(vao_.get());
  glDrawArraysInstanced(GL_TRIANGLES, 0, 3, instances);
}

}  // namespace oitbench
