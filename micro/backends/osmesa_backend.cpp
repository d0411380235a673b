// OSMesa: Mesa's off-screen software context (core profile 4.5 on Mesa 22; removed in Mesa 25.1,
// so this file is built only when CMake finds it).
// glad's header must come before OSMesa's, which includes the system GL header.
#include "gl/gl.hpp"
// clang-format off
#include <GL/osmesa.h>
// clang-format on

#include <vector>

#include "backends/backend.hpp"

namespace oitbench {
namespace {

class OsmesaContext final : public Context {
 public:
  explicit OsmesaContext(const ContextOptions&) {
    const int attribs[] = {OSMESA_FORMAT,
                           OSMESA_RGBA,
                           OSMESA_DEPTH_BITS,
                           24,
                           OSMESA_STENCIL_BITS,
                           8,
                           OSMESA_PROFILE,
                           OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION,
                           4,
                           OSMESA_CONTEXT_MINOR_VERSION,
                           5,
                           0};
    ctx_ = OSMesaCreateContextAttribs(attribs, nullptr);
    if (!ctx_) throw BackendError("OSMesa: OSMesaCreateContextAttribs(core 4.5) returned NULL");
    // The default framebuffer is a 1x1 client buffer: experiments render into FBOs.
    buffer_.resize(4);
    if (!OSMesaMakeCurrent(ctx_, buffer_.data(), GL_UNSIGNED_BYTE, 1, 1))
      throw BackendError("OSMesa: OSMesaMakeCurrent failed");
    if (!gladLoadGL(reinterpret_cast<GLADloadfunc>(OSMesaGetProcAddress)))
      throw BackendError("OSMesa: glad could not load the GL entry points");
  }
  ~OsmesaContext() override { OSMesaDestroyContext(ctx_); }
  std::string backend() const override { return "osmesa"; }
  std::string device() const override { return "OSMesa off-screen buffer"; }

 private:
  OSMesaContext ctx_ = nullptr;
  std::vector<unsigned char> buffer_;
};

}  // namespace

std::unique_ptr<Context> create_osmesa_context(const ContextOptions& o) { return std::make_unique<OsmesaContext>(o); }

}  // namespace oitbench
