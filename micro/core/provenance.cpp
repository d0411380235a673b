#include "core/provenance.hpp"

#include <sys/utsname.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <thread>

#include "core/params.hpp"

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

std::string new_run_id() {
  std::random_device rd;
  unsigned char b[16];
  for (int i = 0; i < 16; i += 4) {
    uint32_t v = rd();
    for (int k = 0; k < 4; ++k) b[i + k] = static_cast<unsigned char>(v >> (8 * k));
  }
  b[6] = static_cast<unsigned char>((b[6] & 0x0f) | 0x40);  // version 4
  b[8] = static_cast<unsigned char>((b[8] & 0x3f) | 0x80);  // variant 10
  static const char* hex = "0123456789abcdef";
  std::string s;
  for (int i = 0; i < 16; ++i) {
    if (i == 4 || i == 6 || i == 8 || i == 10) s += '-';
    s += hex[b[i] >> 4];
    s += hex[b[i] & 15];
  }
  return s;
}

bool is_run_id(const std::string& s) {
  static const std::regex re("[0-9a-f]{8}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{12}");
  return std::regex_match(s, re);
}

namespace {

bool valid_tag_key(const std::string& k) {
  static const std::regex re("[A-Za-z][A-Za-z0-9_.-]{0,63}");
  return std::regex_match(k, re);
}

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

}  // namespace

Tags parse_tags(const std::vector<std::string>& specs, const std::string& option) {
  Tags tags;
  for (const auto& spec : specs) {
    auto eq = spec.find('=');
    if (eq == std::string::npos)
      throw UsageError(option + " " + spec + ": give KEY=VALUE (e.g. " + option + " mesa=22.3.6)");
    std::string key = spec.substr(0, eq), value = spec.substr(eq + 1);
    if (!valid_tag_key(key))
      throw UsageError(option + " " + spec + ": the key '" + key +
                       "' must start with a letter and hold at most 64 of A-Z a-z 0-9 _ . -");
    for (char c : value)
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
        throw UsageError(option + " " + key + "=...: the value holds a control character");
    if (!tags.emplace(key, value).second) throw UsageError(option + " " + key + ": the key is given twice");
  }
  return tags;
}

std::string encode_tags(const Tags& tags) {
  std::string s;
  for (const auto& [k, v] : tags) {
    if (!s.empty()) s += ';';
    s += k + '=';
    for (char c : v) {
      if (c == '%')
        s += "%25";
      else if (c == ';')
        s += "%3B";
      else if (c == '=')
        s += "%3D";
      else
        s += c;
    }
  }
  return s;
}

Tags decode_tags(const std::string& column) {
  Tags tags;
  std::stringstream in(column);
  std::string item;
  while (std::getline(in, item, ';')) {
    auto eq = item.find('=');
    if (eq == std::string::npos) continue;
    std::string value;
    for (size_t i = eq + 1; i < item.size(); ++i) {
      if (item[i] == '%' && i + 2 < item.size() && hex_value(item[i + 1]) >= 0 && hex_value(item[i + 2]) >= 0) {
        value += static_cast<char>(hex_value(item[i + 1]) * 16 + hex_value(item[i + 2]));
        i += 2;
      } else {
        value += item[i];
      }
    }
    tags[item.substr(0, eq)] = value;
  }
  return tags;
}

namespace {

// The x86 and arm extensions LLVM's code generation for llvmpipe can select, in a fixed order.
constexpr const char* kJitIsa[] = {"sse2",     "ssse3",    "sse4_1",   "sse4_2",      "popcnt",      "avx",
                                   "f16c",     "fma",      "avx2",     "bmi2",        "avx512f",     "avx512dq",
                                   "avx512cd", "avx512bw", "avx512vl", "avx512_vnni", "avx512_bf16", "amx_tile",
                                   "asimd",    "sve",      "sve2"};

std::string field(const std::string& text, const std::string& name) {
  std::stringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    auto c = line.find(':');
    if (c == std::string::npos) continue;
    auto key = line.substr(0, c);
    while (!key.empty() && (key.back() == ' ' || key.back() == '\t')) key.pop_back();
    if (key != name) continue;
    auto v = line.substr(c + 1);
    auto b = v.find_first_not_of(" \t");
    return b == std::string::npos ? "" : v.substr(b);
  }
  return "";
}

std::string read_file(const char* path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string fnv1a64_hex(const std::string& s) {
  uint64_t h = 1469598103934665603ull;
  for (unsigned char c : s) {
    h ^= c;
    h *= 1099511628211ull;
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

}  // namespace

MachineIdentity machine_identity(const std::string& cpuinfo, const std::string& meminfo, const std::string& kernel) {
  MachineIdentity m;
  m.cpu_vendor = field(cpuinfo, "vendor_id");
  if (m.cpu_vendor.empty()) m.cpu_vendor = field(cpuinfo, "CPU implementer");
  m.cpu_family = field(cpuinfo, "cpu family");
  if (m.cpu_family.empty()) m.cpu_family = field(cpuinfo, "CPU architecture");
  m.cpu_model_id = field(cpuinfo, "model");
  if (m.cpu_model_id.empty()) m.cpu_model_id = field(cpuinfo, "CPU part");
  m.cpu_stepping = field(cpuinfo, "stepping");
  if (m.cpu_stepping.empty()) m.cpu_stepping = field(cpuinfo, "CPU revision");
  std::string flags = field(cpuinfo, "flags");
  if (flags.empty()) flags = field(cpuinfo, "Features");
  std::set<std::string> have;
  std::stringstream fs(flags);
  for (std::string f; fs >> f;) have.insert(f);
  for (const char* f : kJitIsa)
    if (have.count(f)) m.cpu_isa += (m.cpu_isa.empty() ? "" : " ") + std::string(f);
  std::stringstream ci(cpuinfo);
  for (std::string line; std::getline(ci, line);)
    if (line.rfind("processor", 0) == 0) ++m.cpu_count;
  std::stringstream mi(field(meminfo, "MemTotal"));
  long long kb = 0;
  mi >> kb;
  m.memory_bytes = kb * 1024;
  m.kernel = kernel;
  m.fingerprint = fnv1a64_hex(m.cpu_vendor + "|" + m.cpu_family + "|" + m.cpu_model_id + "|" + m.cpu_stepping + "|" +
                              field(cpuinfo, "model name") + "|" + m.cpu_isa + "|" + std::to_string(m.cpu_count) + "|" +
                              std::to_string(m.memory_bytes) + "|" + m.kernel);
  return m;
}

MachineIdentity this_machine() {
  struct utsname u {};
  std::string kernel;
  if (uname(&u) == 0) kernel = std::string(u.release) + " " + u.version;
  return machine_identity(read_file("/proc/cpuinfo"), read_file("/proc/meminfo"), kernel);
}

LlvmTarget llvm_target(const std::string& gl_renderer) {
  static const std::regex re("LLVM ([0-9][0-9.]*)(, ([0-9]+) bits)?");
  std::smatch m;
  if (!std::regex_search(gl_renderer, m, re)) return {};
  return {m[1].str(), m[3].str()};
}

std::string mesa_version(const std::string& gl_version) {
  static const std::regex re("Mesa [0-9][0-9A-Za-z.+~-]*");
  std::smatch m;
  return std::regex_search(gl_version, m, re) ? m[0].str() : "";
}

}  // namespace oitbench
