// EGL contexts: the surfaceless platform (Mesa; the embedded default) and the device platform
// (EGL_EXT_platform_device: one EGLDevice per GPU or driver, as NVIDIA's and Mesa's EGL expose).
// Either way the context renders into FBOs only.
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <filesystem>
#include <string>

#include "backends/backend.hpp"
#include "gl/gl.hpp"

namespace oitbench {
namespace {

std::string egl_error_name(EGLint e) {
  switch (e) {
    case EGL_SUCCESS:
      return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED:
      return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
      return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
      return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
      return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
      return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
      return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY:
      return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
      return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
      return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE:
      return "EGL_BAD_SURFACE";
    default:
      return "EGL error 0x" + std::to_string(e);
  }
}

struct EglEntryPoints {
  PFNEGLQUERYDEVICESEXTPROC query_devices =
      reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  PFNEGLQUERYDEVICESTRINGEXTPROC query_device_string =
      reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
  PFNEGLQUERYDEVICEATTRIBEXTPROC query_device_attrib =
      reinterpret_cast<PFNEGLQUERYDEVICEATTRIBEXTPROC>(eglGetProcAddress("eglQueryDeviceAttribEXT"));
  PFNEGLGETPLATFORMDISPLAYEXTPROC get_platform_display =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
};

std::vector<EGLDeviceEXT> query_devices(const EglEntryPoints& ep) {
  if (!ep.query_devices) return {};
  EGLint n = 0;
  if (!ep.query_devices(0, nullptr, &n) || n <= 0) return {};
  std::vector<EGLDeviceEXT> devices(static_cast<size_t>(n));
  ep.query_devices(n, devices.data(), &n);
  devices.resize(static_cast<size_t>(n));
  return devices;
}

std::string device_string(const EglEntryPoints& ep, EGLDeviceEXT dev, EGLint name) {
  if (!ep.query_device_string) return "";
  const char* s = ep.query_device_string(dev, name);
  eglGetError();  // a device without the string is not an error worth keeping
  return s ? s : "";
}

// The CUDA ordinal of an NVIDIA EGL device (EGL_NV_device_cuda), else -1.
int cuda_ordinal(const EglEntryPoints& ep, EGLDeviceEXT dev) {
  if (!ep.query_device_attrib || device_string(ep, dev, EGL_EXTENSIONS).find("EGL_NV_device_cuda") == std::string::npos)
    return -1;
  EGLAttrib v = -1;
  if (!ep.query_device_attrib(dev, EGL_CUDA_DEVICE_NV, &v)) {
    eglGetError();
    return -1;
  }
  return static_cast<int>(v);
}

// The PCI bus of a DRM node: /sys/class/drm/<node>/device links to .../0000:01:00.0; empty when unknown.
std::string pci_bus(const std::string& node) {
  if (node.empty()) return "";
  std::error_code ec;
  auto target = std::filesystem::read_symlink(
      std::filesystem::path("/sys/class/drm") / std::filesystem::path(node).filename() / "device", ec);
  return ec ? "" : target.filename().string();
}

DeviceInfo describe_device(const EglEntryPoints& ep, EGLDeviceEXT dev, int index) {
  DeviceInfo d;
  d.index = index;
  d.cuda = cuda_ordinal(ep, dev);
  d.drm_file = device_string(ep, dev, EGL_DRM_DEVICE_FILE_EXT);
  d.render_node = device_string(ep, dev, EGL_DRM_RENDER_NODE_FILE_EXT);
  d.pci_bus = pci_bus(d.drm_file.empty() ? d.render_node : d.drm_file);
  d.extensions = device_string(ep, dev, EGL_EXTENSIONS);
#ifdef EGL_RENDERER_EXT
  d.renderer = device_string(ep, dev, EGL_RENDERER_EXT);
#endif
  return d;
}

class EglContext final : public Context {
 public:
  EglContext(const ContextOptions& o) : backend_(o.backend) {
    EglEntryPoints ep;
    if (!ep.get_platform_display)
      throw BackendError("EGL: eglGetPlatformDisplayEXT is missing (EGL 1.5 / EGL_EXT_platform_base needed)");
    if (o.backend == "egl") {
      display_ = ep.get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
      if (display_ != EGL_NO_DISPLAY && eglInitialize(display_, nullptr, nullptr)) {
        device_ = "EGL_MESA_platform_surfaceless";
      } else {
        // Drivers without the surfaceless platform (some NVIDIA releases): the first EGL device.
        display_ = EGL_NO_DISPLAY;
        open_device(ep, 0);
      }
    } else {
      open_device(ep, o.device);
    }
    if (!eglBindAPI(EGL_OPENGL_API))
      throw BackendError("EGL: eglBindAPI(EGL_OPENGL_API) failed: " + egl_error_name(eglGetError()));
    const EGLint config_attribs[] = {EGL_SURFACE_TYPE,
                                     EGL_PBUFFER_BIT,
                                     EGL_RENDERABLE_TYPE,
                                     EGL_OPENGL_BIT,
                                     EGL_RED_SIZE,
                                     8,
                                     EGL_GREEN_SIZE,
                                     8,
                                     EGL_BLUE_SIZE,
                                     8,
                                     EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    if (!eglChooseConfig(display_, config_attribs, &config, 1, &count) || count == 0)
      throw BackendError("EGL: no config with EGL_PBUFFER_BIT|EGL_OPENGL_BIT on " + device_);
    // 4.6 where the driver offers it (NVIDIA), else 4.5 (Mesa llvmpipe answers 4.6 with EGL_BAD_MATCH).
    for (int minor : {6, 5}) {
      const EGLint ctx_attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                    4,
                                    EGL_CONTEXT_MINOR_VERSION,
                                    minor,
                                    EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                    EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                    EGL_NONE};
      context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, ctx_attribs);
      if (context_ != EGL_NO_CONTEXT) break;
    }
    if (context_ == EGL_NO_CONTEXT) {
      std::string err = egl_error_name(eglGetError());
      std::string offered = offered_version(config);
      eglTerminate(display_);
      display_ = EGL_NO_DISPLAY;
      if (!offered.empty())
        throw ContextUnsupported(
            "the driver offers OpenGL " + offered + " on " + device_ + "; oitbench needs a 4.5 core context", offered);
      throw BackendError("EGL: cannot create a GL 4.5 core context on " + device_ + ": " + err);
    }
    // Surfaceless where EGL_KHR_surfaceless_context exists; a 1x1 pbuffer otherwise.
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) {
      const EGLint pb_attribs[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
      surface_ = eglCreatePbufferSurface(display_, config, pb_attribs);
      if (surface_ == EGL_NO_SURFACE || !eglMakeCurrent(display_, surface_, surface_, context_))
        throw BackendError("EGL: eglMakeCurrent failed: " + egl_error_name(eglGetError()));
    }
    if (!gladLoadGL(reinterpret_cast<GLADloadfunc>(eglGetProcAddress)))
      throw BackendError("EGL: glad could not load the GL entry points");
  }
  ~EglContext() override {
    if (display_ == EGL_NO_DISPLAY) return;
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (surface_ != EGL_NO_SURFACE) eglDestroySurface(display_, surface_);
    if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
    eglTerminate(display_);
  }
  std::string backend() const override { return backend_; }
  std::string device() const override { return device_; }

 private:
  // The best GL version the driver gives instead (a 3.x core, else its default context), for the
  // `unsupported` reason; empty when it gives none.
  std::string offered_version(EGLConfig config) {
    using GetString = const unsigned char* (*)(unsigned);
    auto get_string = reinterpret_cast<GetString>(eglGetProcAddress("glGetString"));
    const EGLint core33[] = {
        EGL_CONTEXT_MAJOR_VERSION,           3,       EGL_CONTEXT_MINOR_VERSION, 3, EGL_CONTEXT_OPENGL_PROFILE_MASK,
        EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    const EGLint plain[] = {EGL_NONE};
    for (const EGLint* attribs : {core33, plain}) {
      EGLContext c = eglCreateContext(display_, config, EGL_NO_CONTEXT, attribs);
      if (c == EGL_NO_CONTEXT) continue;
      std::string version;
      if (get_string && eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, c)) {
        const unsigned char* v = get_string(0x1F02);  // GL_VERSION
        if (v) version = reinterpret_cast<const char*>(v);
        eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      }
      eglDestroyContext(display_, c);
      if (!version.empty()) return version;
    }
    return "";
  }

  void open_device(const EglEntryPoints& ep, int index) {
    auto devices = query_devices(ep);
    if (devices.empty()) throw BackendError("EGL: no EGL devices (EGL_EXT_device_enumeration missing or empty)");
    if (index < 0 || index >= static_cast<int>(devices.size()))
      throw BackendError("EGL: --device " + std::to_string(index) + " out of range; " + std::to_string(devices.size()) +
                         " device(s): see `oitbench info --backend egl-device`");
    auto dev = devices[static_cast<size_t>(index)];
    display_ = ep.get_platform_display(EGL_PLATFORM_DEVICE_EXT, dev, nullptr);
    if (display_ == EGL_NO_DISPLAY || !eglInitialize(display_, nullptr, nullptr))
      throw BackendError("EGL: cannot initialize EGL device " + std::to_string(index) + ": " +
                         egl_error_name(eglGetError()));
    DeviceInfo d = describe_device(ep, dev, index);
    device_ = "EGL device " + std::to_string(index) + " (" + d.extensions +
              (d.drm_file.empty() ? "" : ", " + d.drm_file) + (d.pci_bus.empty() ? "" : ", PCI " + d.pci_bus) + ")";
  }

  std::string backend_, device_;
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
  EGLSurface surface_ = EGL_NO_SURFACE;
};

}  // namespace

std::unique_ptr<Context> create_egl_context(const ContextOptions& o) { return std::make_unique<EglContext>(o); }

std::vector<DeviceInfo> list_egl_devices() {
  EglEntryPoints ep;
  std::vector<DeviceInfo> out;
  auto devices = query_devices(ep);
  for (size_t i = 0; i < devices.size(); ++i) out.push_back(describe_device(ep, devices[i], static_cast<int>(i)));
  return out;
}

}  // namespace oitbench
