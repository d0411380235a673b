#include "core/provenance.hpp"

#include <unistd.h>

#include <cstdlib>
#include <ctime>
#include <fstream>
#include <thread>

namespace oitbench {

std::string utc_now() {
  auto t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

std::string host_name() {
  char buf[256] = {};
  gethostname(buf, sizeof buf - 1);
  return buf;
}

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) {
      auto c = line.find(':');
      return c == std::string::npos ? "" : line.substr(c + 2);
    }
  return "";
}

std::string recorded_env() {
  static const char* const names[] = {
      "LP_NATIVE_VECTOR_WIDTH",      "GALLIUM_DRIVER",        "LIBGL_ALWAYS_SOFTWARE",
      "MESA_SHADER_CACHE_DISABLE",   "MESA_SHADER_CACHE_DIR", "MESA_GL_VERSION_OVERRIDE",
      "MESA_LOADER_DRIVER_OVERRIDE", "EGL_PLATFORM",          "__GL_THREADED_OPTIMIZATIONS",
      "__GL_SHADER_DISK_CACHE",      "OITBENCH_SHADERS",      "OITBENCH_NVML_LIBRARY"};
  std::string s;
  for (const char* n : names)
    if (const char* v = std::getenv(n)) s += (s.empty() ? "" : ";") + std::string(n) + "=" + v;
  return s;
}

std::string lp_num_threads() {
  if (const char* v = std::getenv("LP_NUM_THREADS")) return v;
  return "unset(" + std::to_string(std::thread::hardware_concurrency()) + " cores)";
}

}  // namespace oitbench
