#include "gl/render_target.hpp"

#include <cstdio>
#include <stdexcept>
#include <string>

namespace oitbench {

namespace {
std::string hex(GLenum v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%04x", static_cast<unsigned>(v));
  return buf;
}
}  // namespace

std::string render_target_size_problem(int width, int height) {
  struct Limit {
    const char* name;
    GLenum e;
    int index;  // into the values glGetIntegerv returns
    bool height;
  };
  static const Limit limits[] = {{"GL_MAX_TEXTURE_SIZE", GL_MAX_TEXTURE_SIZE, 0, false},
                                 {"GL_MAX_TEXTURE_SIZE", GL_MAX_TEXTURE_SIZE, 0, true},
                                 {"GL_MAX_RENDERBUFFER_SIZE", GL_MAX_RENDERBUFFER_SIZE, 0, false},
                                 {"GL_MAX_RENDERBUFFER_SIZE", GL_MAX_RENDERBUFFER_SIZE, 0, true},
                                 {"GL_MAX_FRAMEBUFFER_WIDTH", GL_MAX_FRAMEBUFFER_WIDTH, 0, false},
                                 {"GL_MAX_FRAMEBUFFER_HEIGHT", GL_MAX_FRAMEBUFFER_HEIGHT, 0, true},
                                 {"GL_MAX_VIEWPORT_DIMS[0]", GL_MAX_VIEWPORT_DIMS, 0, false},
                                 {"GL_MAX_VIEWPORT_DIMS[1]", GL_MAX_VIEWPORT_DIMS, 1, true}};
  for (const auto& l : limits) {
    GLint v[2] = {0, 0};
    glGetIntegerv(l.e, v);
    if (glGetError() != GL_NO_ERROR || v[l.index] <= 0) continue;
    const int side = l.height ? height : width;
    if (side > v[l.index])
      return std::to_string(width) + "x" + std::to_string(height) + ": the " + (l.height ? "height " : "width ") +
             std::to_string(side) + " is past " + l.name + " = " + std::to_string(v[l.index]);
  }
  return "";
}

RenderTarget::RenderTarget(int width, int height, GLenum color_format, bool depth_stencil)
    : width_(width), height_(height) {
  if (auto problem = render_target_size_problem(width, height); !problem.empty())
    throw RenderTargetUnavailable("render target " + problem);
  while (glGetError() != GL_NO_ERROR) {
  }
  fbo_ = gl::make_framebuffer();
  color_ = gl::make_texture(GL_TEXTURE_2D);
  glTextureStorage2D(color_.get(), 1, color_format, width, height);
  GLenum storage_error = glGetError();
  glNamedFramebufferTexture(fbo_.get(), GL_COLOR_ATTACHMENT0, color_.get(), 0);
  if (depth_stencil) {
    depth_stencil_ = gl::make_renderbuffer();
    glNamedRenderbufferStorage(depth_stencil_.get(), GL_DEPTH24_STENCIL8, width, height);
    if (storage_error == GL_NO_ERROR) storage_error = glGetError();
    glNamedFramebufferRenderbuffer(fbo_.get(), GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, depth_stencil_.get());
  }
  GLenum status = glCheckNamedFramebufferStatus(fbo_.get(), GL_FRAMEBUFFER);
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  if (storage_error == GL_OUT_OF_MEMORY)
    throw RenderTargetUnavailable("render target " + size + ": the driver could not allocate it (GL_OUT_OF_MEMORY)");
  if (status != GL_FRAMEBUFFER_COMPLETE)
    throw RenderTargetUnavailable("render target " + size + " incomplete (framebuffer status " + hex(status) +
                                  (storage_error != GL_NO_ERROR ? ", storage error " + hex(storage_error) : "") +
                                  "): the driver cannot make it at this size");
}

void RenderTarget::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
  glViewport(0, 0, width_, height_);
}

void RenderTarget::bind_cleared(float r, float g, float b, float a) const {
  bind();
  const float rgba[4] = {r, g, b, a};
  glClearNamedFramebufferfv(fbo_.get(), GL_COLOR, 0, rgba);
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
