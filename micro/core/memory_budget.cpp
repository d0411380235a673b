#include "core/memory_budget.hpp"

#include <sys/resource.h>

#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/registry.hpp"
#include "gl/gl.hpp"

namespace oitbench {

namespace {

// GL_NVX_gpu_memory_info and GL_ATI_meminfo: not in glad's core profile header.
constexpr GLenum kNvxAvailableVidmemKiB = 0x9049;  // GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX
constexpr GLenum kAtiVboFreeMemoryKiB = 0x87FB;    // VBO_FREE_MEMORY_ATI: 4 values, [0] the total free

std::string fixed(double v, int digits) {
  std::ostringstream s;
  s.precision(digits);
  s << std::fixed << v;
  return s.str();
}

// A /proc file's "Key: N kB" line, in bytes; 0 when absent.
unsigned long long proc_kib(const std::string& file, const std::string& key) {
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(key + ":", 0) == 0) {
      std::istringstream s(line.substr(key.size() + 1));
      unsigned long long kib = 0;
      s >> kib;
      return kib * 1024;
    }
  return 0;
}

// What an rlimit leaves this process: the soft limit minus what it counts now; nothing when unlimited.
void apply_rlimit(MemoryLimit& limit, int resource, const char* name, unsigned long long used) {
  rlimit r{};
  if (getrlimit(resource, &r) != 0 || r.rlim_cur == RLIM_INFINITY) return;
  unsigned long long left = r.rlim_cur > used ? r.rlim_cur - used : 1;
  if (!limit.known() || left < limit.bytes)
    limit = {left, std::string(name) + " " + format_bytes(r.rlim_cur) + " less " + format_bytes(used) + " in use"};
}

std::string need_text(unsigned long long bytes, const char* kind, const std::string& what) {
  return format_bytes(bytes) + " of " + kind + " memory" + (what.empty() ? "" : " for " + what);
}

}  // namespace

std::string format_bytes(unsigned long long bytes) {
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB"};
  double v = static_cast<double>(bytes);
  int u = 0;
  while (v >= 1024.0 && u < 5) {
    v /= 1024.0;
    ++u;
  }
  if (u == 0) return std::to_string(bytes) + " B";
  return fixed(v, v < 10 ? 2 : v < 100 ? 1 : 0) + " " + units[u];
}

std::string format_count(unsigned long long n) {
  if (n < 1000000) return std::to_string(n);
  const double v = static_cast<double>(n);
  if (v < 1e9) return fixed(v / 1e6, v < 1e7 ? 2 : v < 1e8 ? 1 : 0) + " M";
  return fixed(v / 1e9, v < 1e10 ? 2 : 1) + " G";
}

unsigned long long parse_byte_size(const std::string& text) {
  const std::string accepted =
      "a size in bytes with an optional unit K, M, G or T (powers of 1024; KiB, MB, ... also), e.g. 8G, 512M, 1.5GiB";
  std::string t = text;
  while (!t.empty() && std::isspace(static_cast<unsigned char>(t.back()))) t.pop_back();
  size_t digits = 0;
  while (digits < t.size() && (std::isdigit(static_cast<unsigned char>(t[digits])) || t[digits] == '.')) ++digits;
  if (digits == 0) throw std::invalid_argument("'" + text + "' is not " + accepted);
  double value = 0;
  try {
    size_t used = 0;
    value = std::stod(t.substr(0, digits), &used);
    if (used != digits) throw std::invalid_argument("");
  } catch (const std::exception&) {
    throw std::invalid_argument("'" + text + "' is not " + accepted);
  }
  std::string unit = t.substr(digits);
  for (auto& c : unit) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  if (unit.size() == 3 && unit.substr(1) == "IB") unit = unit.substr(0, 1);
  if (unit.size() == 2 && unit[1] == 'B') unit = unit.substr(0, 1);
  const std::string prefixes = "KMGT";
  double scale = 1;
  if (unit == "B" || unit.empty())
    scale = 1;
  else if (unit.size() == 1 && prefixes.find(unit[0]) != std::string::npos)
    scale = std::pow(1024.0, static_cast<double>(prefixes.find(unit[0]) + 1));
  else
    throw std::invalid_argument("'" + text + "': unknown unit '" + t.substr(digits) + "'; " + accepted);
  const double bytes = value * scale;
  if (!std::isfinite(bytes) || bytes < 1 || bytes > 1125899906842624.0)  // 1 B .. 1 PiB
    throw std::invalid_argument("'" + text + "' is outside 1 B to 1 PiB; " + accepted);
  return static_cast<unsigned long long>(bytes);
}

MemoryLimit cpu_memory_limit() {
  MemoryLimit limit;
  if (unsigned long long avail = proc_kib("/proc/meminfo", "MemAvailable"))
    limit = {avail, "MemAvailable " + format_bytes(avail)};
  apply_rlimit(limit, RLIMIT_AS, "RLIMIT_AS", proc_kib("/proc/self/status", "VmSize"));
  apply_rlimit(limit, RLIMIT_DATA, "RLIMIT_DATA", proc_kib("/proc/self/status", "VmData"));
  return limit;
}

MemoryLimits current_memory_limits(bool software, bool nvx, bool ati, std::optional<unsigned long long> cpu_override) {
  MemoryLimits l;
  l.cpu = cpu_override ? MemoryLimit{*cpu_override, "--memory-limit"} : cpu_memory_limit();
  l.shared = software;
  if (software) return l;
  GLint kib[4] = {0, 0, 0, 0};
  if (nvx) {
    glGetIntegerv(kNvxAvailableVidmemKiB, kib);
    if (kib[0] > 0) l.gpu = {static_cast<unsigned long long>(kib[0]) * 1024, "GL_NVX_gpu_memory_info's free memory"};
  } else if (ati) {
    glGetIntegerv(kAtiVboFreeMemoryKiB, kib);
    if (kib[0] > 0) l.gpu = {static_cast<unsigned long long>(kib[0]) * 1024, "GL_ATI_meminfo's free memory"};
  }
  while (glGetError() != GL_NO_ERROR) {
  }
  return l;
}

std::string memory_refusal(const MemoryNeed& need, const MemoryLimits& limits) {
  if (limits.shared) {
    const unsigned long long total = need.gpu_bytes + need.cpu_bytes;
    if (!limits.cpu.known() || total <= limits.cpu.bytes) return "";
    std::string parts;
    if (need.gpu_bytes) parts += need_text(need.gpu_bytes, "GPU", need.gpu_what);
    if (need.cpu_bytes) parts += (parts.empty() ? "" : " and ") + need_text(need.cpu_bytes, "CPU", need.cpu_what);
    return "needs " + format_bytes(total) + " (" + parts +
           "; a software renderer's GPU buffers are CPU memory); limit " + format_bytes(limits.cpu.bytes) + " (" +
           limits.cpu.source + ")";
  }
  if (limits.cpu.known() && need.cpu_bytes > limits.cpu.bytes)
    return "needs " + need_text(need.cpu_bytes, "CPU", need.cpu_what) + "; limit " + format_bytes(limits.cpu.bytes) +
           " (" + limits.cpu.source + ")";
  if (limits.gpu.known() && need.gpu_bytes > limits.gpu.bytes)
    return "needs " + need_text(need.gpu_bytes, "GPU", need.gpu_what) + "; limit " + format_bytes(limits.gpu.bytes) +
           " (" + limits.gpu.source + ")";
  return "";
}

void require_memory(const MemoryNeed& need, const MemoryLimits& limits, const std::string& what) {
  if (auto why = memory_refusal(need, limits); !why.empty()) throw Unsupported(what + " " + why);
}

MemoryNeed combined(MemoryNeed a, const MemoryNeed& b) {
  auto join = [](const std::string& x, const std::string& y) { return x.empty() ? y : y.empty() ? x : x + " + " + y; };
  a.gpu_bytes += b.gpu_bytes;
  a.cpu_bytes += b.cpu_bytes;
  a.gpu_what = join(a.gpu_what, b.gpu_what);
  a.cpu_what = join(a.cpu_what, b.cpu_what);
  return a;
}

}  // namespace oitbench
