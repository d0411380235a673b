// GLFW: a real window (interactive use, and tests under xvfb-run). Experiments still render into
// FBOs; the window is for presenting and for drivers that only give contexts with a window.
#include "gl/gl.hpp"
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <string>

#include "backends/backend.hpp"

namespace oitbench {
namespace {

class GlfwContext final : public Context {
 public:
  explicit GlfwContext(const ContextOptions& o) {
    glfwSetErrorCallback(nullptr);
    if (!glfwInit()) {
      const char* msg = nullptr;
      glfwGetError(&msg);
      throw BackendError(std::string("GLFW: glfwInit failed (no display? run under xvfb-run -a): ") +
                         (msg ? msg : "?"));
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_VISIBLE, o.visible ? GLFW_TRUE : GLFW_FALSE);
    window_ = glfwCreateWindow(o.width, o.height, "oitbench", nullptr, nullptr);
    if (!window_) {
      const char* msg = nullptr;
      glfwGetError(&msg);
      glfwTerminate();
      throw BackendError(std::string("GLFW: cannot create a GL 4.5 core window: ") + (msg ? msg : "?"));
    }
    glfwMakeContextCurrent(window_);
    glfwSwapInterval(0);
    if (!gladLoadGL(reinterpret_cast<GLADloadfunc>(glfwGetProcAddress)))
      throw BackendError("GLFW: glad could not load the GL entry points");
  }
  ~GlfwContext() override {
    glfwDestroyWindow(window_);
    glfwTerminate();
  }
  std::string backend() const override { return "glfw"; }
  std::string device() const override { return "GLFW window"; }
  void swap_buffers() override {
    glfwSwapBuffers(window_);
    glfwPollEvents();
  }
  bool window_should_close() override { return glfwWindowShouldClose(window_); }
  void* native_window() override { return window_; }

 private:
  GLFWwindow* window_ = nullptr;
};

}  // namespace

std::unique_ptr<Context> create_glfw_context(const ContextOptions& o) { return std::make_unique<GlfwContext>(o); }

}  // namespace oitbench
