#pragma once
// The headless drawing surface every experiment shares: an FBO with a colour attachment (and
// optionally depth-stencil), a full-screen triangle, and read-back.
#include <stdexcept>
#include <vector>

#include "gl/gl_objects.hpp"

namespace oitbench {

// The driver cannot make a render target of this size (past its limits, or out of memory): the runner
// writes the case as `unsupported` with this reason.
class RenderTargetUnavailable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Empty when width x height is within the driver's framebuffer, texture, renderbuffer and viewport
// limits; else which limit it passes ("1920x20000: GL_MAX_TEXTURE_SIZE is 16384").
std::string render_target_size_problem(int width, int height);

class RenderTarget {
 public:
  // Throws RenderTargetUnavailable when the driver cannot make it (render_target_size_problem, or an
  // allocation that fails).
  RenderTarget(int width, int height, GLenum color_format = GL_RGBA32F, bool depth_stencil = false);
  void bind() const;  // binds the FBO and sets the viewport
  // bind(), then clears the colour to (r, g, b, a): the start of a pass that draws into the whole target.
  void bind_cleared(float r, float g, float b, float a) const;
  int width() const { return width_; }
  int height() const { return height_; }
  GLuint framebuffer() const { return fbo_.get(); }
  GLuint color_texture() const { return color_.get(); }
  std::vector<float> read_rgba32f() const;   // row-major from the bottom row, 4 floats per pixel
  std::vector<unsigned> read_r32ui() const;  // for GL_R32UI targets

 private:
  int width_, height_;
  gl::Framebuffer fbo_;
  gl::Texture color_;
  gl::Renderbuffer depth_stencil_;
};

// Draws one triangle covering the viewport (shaders/common/fullscreen.vert, no vertex buffer).
class FullscreenTriangle {
 public:
  FullscreenTriangle() : vao_(gl::make_vertex_array()) {}
  void draw(GLsizei instances = 1) const;

 private:
  gl::VertexArray vao_;
};

}  // namespace oitbench
