#include "backends/backend.hpp"

#include <algorithm>
#include <cstdio>

#include "gl/gl.hpp"

namespace oitbench {

std::vector<std::string> compiled_backends() {
  std::vector<std::string> b{"egl", "egl-device"};
#ifdef OITBENCH_HAVE_OSMESA
  b.push_back("osmesa");
#endif
#ifdef OITBENCH_HAVE_GLFW
  b.push_back("glfw");
#endif
  return b;
}

namespace {
void GLAD_API_PTR debug_callback(GLenum, GLenum type, GLuint, GLenum severity, GLsizei, const GLchar* msg,
                                 const void*) {
  if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
  std::fprintf(stderr, "oitbench: GL debug (%s): %s\n", type == GL_DEBUG_TYPE_ERROR ? "error" : "message", msg);
}
}  // namespace

std::unique_ptr<Context> create_context(const ContextOptions& o) {
  std::unique_ptr<Context> ctx;
  if (o.backend == "egl" || o.backend == "egl-device") {
    ctx = create_egl_context(o);
  } else if (o.backend == "osmesa") {
#ifdef OITBENCH_HAVE_OSMESA
    ctx = create_osmesa_context(o);
#else
    throw BackendError(
        "backend 'osmesa' is not part of this build (OSMesa was not found at configure time; Mesa 25.1 removed it)");
#endif
  } else if (o.backend == "glfw") {
#ifdef OITBENCH_HAVE_GLFW
    ctx = create_glfw_context(o);
#else
    throw BackendError("backend 'glfw' is not part of this build (libglfw3-dev was not found at configure time)");
#endif
  } else {
    std::string list;
    for (const auto& b : compiled_backends()) list += (list.empty() ? "" : ", ") + b;
    throw BackendError("unknown backend '" + o.backend + "'; valid backends: " + list);
  }
  if (o.debug && GLAD_GL_VERSION_4_3) {
    glEnable(GL_DEBUG_OUTPUT);
    glDebugMessageCallback(debug_callback, nullptr);
  }
  return ctx;
}

GlInfo GlInfo::query() {
  GlInfo info;
  auto str = [](GLenum e) {
    const auto* s = glGetString(e);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string();
  };
  info.vendor = str(GL_VENDOR);
  info.renderer = str(GL_RENDERER);
  info.version = str(GL_VERSION);
  info.glsl_version = str(GL_SHADING_LANGUAGE_VERSION);
  glGetIntegerv(GL_MAJOR_VERSION, &info.major);
  glGetIntegerv(GL_MINOR_VERSION, &info.minor);
  GLint n = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &n);
  for (GLint i = 0; i < n; ++i)
    info.extensions.insert(reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, static_cast<GLuint>(i))));
  struct Limit {
    const char* name;
    GLenum e;
  };
  static const Limit limits[] = {
      {"GL_MAX_SHADER_STORAGE_BLOCK_SIZE", GL_MAX_SHADER_STORAGE_BLOCK_SIZE},
      {"GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS", GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS},
      {"GL_MAX_FRAGMENT_SHADER_STORAGE_BLOCKS", GL_MAX_FRAGMENT_SHADER_STORAGE_BLOCKS},
      {"GL_MAX_FRAGMENT_IMAGE_UNIFORMS", GL_MAX_FRAGMENT_IMAGE_UNIFORMS},
      {"GL_MAX_IMAGE_UNITS", GL_MAX_IMAGE_UNITS},
      {"GL_MAX_FRAGMENT_ATOMIC_COUNTERS", GL_MAX_FRAGMENT_ATOMIC_COUNTERS},
      {"GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS", GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS},
      {"GL_MAX_COMPUTE_SHARED_MEMORY_SIZE", GL_MAX_COMPUTE_SHARED_MEMORY_SIZE},
      {"GL_MAX_TEXTURE_SIZE", GL_MAX_TEXTURE_SIZE},
      {"GL_MAX_3D_TEXTURE_SIZE", GL_MAX_3D_TEXTURE_SIZE},
      {"GL_MAX_TEXTURE_BUFFER_SIZE", GL_MAX_TEXTURE_BUFFER_SIZE},
      {"GL_MAX_SAMPLES", GL_MAX_SAMPLES},
      {"GL_MAX_RENDERBUFFER_SIZE", GL_MAX_RENDERBUFFER_SIZE},
      {"GL_MAX_FRAMEBUFFER_WIDTH", GL_MAX_FRAMEBUFFER_WIDTH},
  };
  for (const auto& l : limits) {
    GLint64 v = 0;
    glGetInteger64v(l.e, &v);
    if (glGetError() == GL_NO_ERROR) info.limits[l.name] = v;
  }
  GLint bits = 0;
  glGetQueryiv(GL_TIME_ELAPSED, GL_QUERY_COUNTER_BITS, &bits);
  info.limits["GL_QUERY_COUNTER_BITS(TIME_ELAPSED)"] = bits;
  // Stencil bits of the FBO attachments the experiments use (framebuffer 0 may not exist headless).
  GLuint rb = 0, fb = 0;
  glCreateRenderbuffers(1, &rb);
  glNamedRenderbufferStorage(rb, GL_DEPTH24_STENCIL8, 4, 4);
  GLint stencil = 0;
  glGetNamedRenderbufferParameteriv(rb, GL_RENDERBUFFER_STENCIL_SIZE, &stencil);
  info.limits["stencil_bits(GL_DEPTH24_STENCIL8)"] = stencil;
  glDeleteRenderbuffers(1, &rb);
  (void)fb;
  while (glGetError() != GL_NO_ERROR) {
  }
  return info;
}

bool GlInfo::has_fragment_shader_interlock() const {
  return has_extension("GL_ARB_fragment_shader_interlock") || has_extension("GL_NV_fragment_shader_interlock") ||
         has_extension("GL_INTEL_fragment_shader_ordering");
}

bool GlInfo::is_software_renderer() const {
  for (const char* s : {"llvmpipe", "softpipe", "swrast", "SwiftShader", "Software Rasterizer"})
    if (renderer.find(s) != std::string::npos) return true;
  return false;
}

long long GlInfo::limit(const std::string& name) const {
  auto it = limits.find(name);
  return it == limits.end() ? 0 : it->second;
}

}  // namespace oitbench
