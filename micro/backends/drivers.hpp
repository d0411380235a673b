#pragma once
// GL drivers as a choice: on one machine the same binary can run on Mesa's llvmpipe, zink over
// lavapipe (GL on Vulkan on a CPU), softpipe, or whatever the loader gives (a GPU's driver), and
// on a machine with several EGL devices on any of them. A driver is chosen before the context
// exists: Mesa's loader reads its environment when EGL is initialised.
#include <string>
#include <utility>
#include <vector>

#include "backends/backend.hpp"

namespace oitbench {

struct DriverSpec {
  std::string name;                                      // default | llvmpipe | zink | softpipe | egl-device-N
  std::string description;                               // in words, for `info --drivers` and errors
  std::vector<std::pair<std::string, std::string>> env;  // set before the context is created
  std::string backend;  // empty: the caller's --backend; else the backend this driver needs
  int device = -1;      // egl-device-N: the EGL device index
};

// The drivers oitbench knows how to select (EGL devices are appended by `info --drivers` once
// enumerated; `egl-device-N` is accepted for any N).
std::vector<DriverSpec> known_drivers();
// Throws BackendError listing the valid names for an unknown one.
DriverSpec find_driver(const std::string& name);
// Sets the driver's environment (and XDG_RUNTIME_DIR where unset, which zink wants) and, for an EGL
// device, the backend and device. Call before create_context.
void apply_driver(const DriverSpec& driver, ContextOptions& options);
// A short name for what a context runs on, from its GL strings: llvmpipe, zink-lavapipe, softpipe,
// nvidia-h200, amd-radeon-rx-7900-xtx, ...: the `driver` column and results/<slug>/.
std::string driver_slug(const GlInfo& gl);

}  // namespace oitbench
