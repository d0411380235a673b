#include "backends/drivers.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cstdlib>
#include <filesystem>

namespace oitbench {

std::vector<DriverSpec> known_drivers() {
  // On a machine whose EGL vendor is not Mesa (glvnd picks NVIDIA's first), Mesa's software
  // drivers need Mesa's vendor file named explicitly.
  std::vector<std::pair<std::string, std::string>> mesa_vendor;
  for (const char* f : {"/usr/share/glvnd/egl_vendor.d/50_mesa.json", "/etc/glvnd/egl_vendor.d/50_mesa.json"})
    if (std::filesystem::exists(f)) {
      mesa_vendor.push_back({"__EGL_VENDOR_LIBRARY_FILENAMES", f});
      break;
    }
  auto with_vendor = [&](std::vector<std::pair<std::string, std::string>> env) {
    env.insert(env.begin(), mesa_vendor.begin(), mesa_vendor.end());
    return env;
  };
  return {
      {"default", "whatever the GL loader gives (the machine's GPU driver, else Mesa's default)", {}, "", -1},
      {"llvmpipe", "Mesa llvmpipe: the CPU rasterizer, JIT-compiled by LLVM (the embedded default)",
       with_vendor({{"LIBGL_ALWAYS_SOFTWARE", "1"}, {"GALLIUM_DRIVER", "llvmpipe"}}), "", -1},
      {"zink",
       "Mesa zink over lavapipe: GL 4.6 translated to Vulkan, run by lavapipe on the CPU "
       "(apt-get install mesa-vulkan-drivers)",
       with_vendor({{"LIBGL_ALWAYS_SOFTWARE", "1"}, {"GALLIUM_DRIVER", "zink"}}), "", -1},
      {"softpipe", "Mesa softpipe: the reference CPU rasterizer (GL 3.3 core: too old for oitbench's 4.5)",
       with_vendor({{"LIBGL_ALWAYS_SOFTWARE", "1"}, {"GALLIUM_DRIVER", "softpipe"}}), "", -1},
  };
}

DriverSpec find_driver(const std::string& name) {
  for (const auto& d : known_drivers())
    if (d.name == name) return d;
  const std::string prefix = "egl-device-";
  if (name.rfind(prefix, 0) == 0 && name.size() > prefix.size()) {
    std::string n = name.substr(prefix.size());
    bool digits = !n.empty() && n.size() < 4;
    for (char c : n) digits = digits && std::isdigit(static_cast<unsigned char>(c));
    if (digits) return {name, "EGL device " + n + " (see: oitbench info --drivers)", {}, "egl-device", std::stoi(n)};
  }
  std::string valid;
  for (const auto& d : known_drivers()) valid += (valid.empty() ? "" : ", ") + d.name;
  throw BackendError("unknown driver '" + name + "'; valid drivers: " + valid +
                     ", egl-device-N (see: oitbench info --drivers)");
}

void apply_driver(const DriverSpec& driver, ContextOptions& options) {
  for (const auto& [k, v] : driver.env) setenv(k.c_str(), v.c_str(), 1);
  if (driver.name == "zink" && !std::getenv("XDG_RUNTIME_DIR")) {
    // zink's Vulkan loader complains twice on stderr without one; a private folder silences it.
    std::string dir = std::filesystem::temp_directory_path() / ("oitbench-xdg-" + std::to_string(getuid()));
    mkdir(dir.c_str(), 0700);
    setenv("XDG_RUNTIME_DIR", dir.c_str(), 1);
  }
  if (!driver.backend.empty()) options.backend = driver.backend;
  if (driver.device >= 0) options.device = driver.device;
  options.driver = driver.name;
}

std::string driver_slug(const GlInfo& gl) {
  auto slug = [](const std::string& s) {
    std::string out;
    for (char c : s) {
      unsigned char u = static_cast<unsigned char>(c);
      if (std::isalnum(u))
        out += static_cast<char>(std::tolower(u));
      else if (!out.empty() && out.back() != '-')
        out += '-';
    }
    while (!out.empty() && out.back() == '-') out.pop_back();
    return out;
  };
  const std::string& r = gl.renderer;
  if (r.rfind("zink", 0) == 0)
    return r.find("llvmpipe") != std::string::npos ? "zink-lavapipe" : "zink-" + slug(r.substr(4));
  for (const char* sw : {"llvmpipe", "softpipe", "swrast", "SwiftShader"})
    if (r.find(sw) != std::string::npos) return slug(sw);
  // Hardware: the renderer up to its first '/' or '(' ("NVIDIA H200/PCIe/SSE2" -> nvidia-h200).
  std::string head = r.substr(0, r.find_first_of("/("));
  std::string s = slug(head);
  return s.empty() ? "unknown" : s;
}

}  // namespace oitbench
