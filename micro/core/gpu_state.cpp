#include "core/gpu_state.hpp"

#include <dlfcn.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>

namespace oitbench {

// The few NVML entry points used, declared here from nvml.h's prototypes (no header, no link dependency):
//   nvmlReturn_t nvmlInit_v2(void);
//   nvmlReturn_t nvmlShutdown(void);
//   nvmlReturn_t nvmlSystemGetDriverVersion(char *version, unsigned int length);
//   nvmlReturn_t nvmlDeviceGetCount_v2(unsigned int *deviceCount);
//   nvmlReturn_t nvmlDeviceGetHandleByIndex_v2(unsigned int index, nvmlDevice_t *device);
//   nvmlReturn_t nvmlDeviceGetName(nvmlDevice_t device, char *name, unsigned int length);
//   nvmlReturn_t nvmlDeviceGetClockInfo(nvmlDevice_t device, nvmlClockType_t type, unsigned int *clock);  // MHz
//   nvmlReturn_t nvmlDeviceGetTemperature(nvmlDevice_t device, nvmlTemperatureSensors_t sensorType,
//                                         unsigned int *temp);                                          // deg C
//   nvmlReturn_t nvmlDeviceGetPowerUsage(nvmlDevice_t device, unsigned int *power);                   // mW
// and, where the library has them (the device's identity; empty otherwise):
//   nvmlReturn_t nvmlDeviceGetVbiosVersion(nvmlDevice_t device, char *version, unsigned int length);
//   nvmlReturn_t nvmlDeviceGetPciInfo_v3(nvmlDevice_t device, nvmlPciInfo_t *pci);
// nvmlReturn_t and the two enums are C enums (int); nvmlDevice_t is an opaque pointer.
namespace {
using NvmlReturn = int;
using NvmlDevice = struct NvmlDeviceOpaque*;
constexpr NvmlReturn kNvmlSuccess = 0;
constexpr int kNvmlClockSm = 1, kNvmlClockMem = 2;  // nvmlClockType_t: NVML_CLOCK_SM, NVML_CLOCK_MEM
constexpr int kNvmlTemperatureGpu = 0;              // nvmlTemperatureSensors_t: NVML_TEMPERATURE_GPU
constexpr unsigned kNameBuffer = 96;                // NVML_DEVICE_NAME_V2_BUFFER_SIZE
constexpr unsigned kVersionBuffer = 80;             // NVML_SYSTEM_DRIVER_VERSION_BUFFER_SIZE
// nvmlPciInfo_t as nvml.h lays it out; pciDeviceId is the device ID in the high 16 bits, the vendor's below.
struct NvmlPciInfo {
  char bus_id_legacy[16];
  unsigned domain, bus, device, pci_device_id, pci_subsystem_id;
  char bus_id[32];
};

// "10de:2335": a PCI vendor and device ID as lspci -n writes them.
std::string pci_id_text(unsigned vendor, unsigned device) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%04x:%04x", vendor & 0xffffu, device & 0xffffu);
  return buf;
}

// The first line of a sysfs file, without its newline; empty where it cannot be read.
std::string first_line(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  if (!in || !std::getline(in, line)) return "";
  while (!line.empty() && (line.back() == '\n' || line.back() == '\r' || line.back() == ' ')) line.pop_back();
  return line;
}

// A PCI address as sysfs names it (0000:01:00.0): hex digits, ':' and '.', nothing that leaves the folder.
bool is_pci_address(const std::string& s) {
  if (s.empty() || s.find("..") != std::string::npos) return false;
  for (char c : s)
    if (!std::isxdigit(static_cast<unsigned char>(c)) && c != ':' && c != '.') return false;
  return true;
}

template <typename F>
bool load(void* lib, const char* name, F& fn) {
  fn = reinterpret_cast<F>(dlsym(lib, name));
  return fn != nullptr;
}

std::string cell(const std::optional<unsigned>& v) { return v ? std::to_string(*v) : ""; }
std::string cell(const std::optional<double>& v) {
  if (!v) return "";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", *v);
  return buf;
}
}  // namespace

struct GpuMonitor::Nvml {
  void* lib = nullptr;
  NvmlDevice device = nullptr;
  NvmlReturn (*init)() = nullptr;
  NvmlReturn (*shutdown)() = nullptr;
  NvmlReturn (*driver_version)(char*, unsigned) = nullptr;
  NvmlReturn (*device_count)(unsigned*) = nullptr;
  NvmlReturn (*device_by_index)(unsigned, NvmlDevice*) = nullptr;
  NvmlReturn (*device_name)(NvmlDevice, char*, unsigned) = nullptr;
  NvmlReturn (*clock_info)(NvmlDevice, int, unsigned*) = nullptr;
  NvmlReturn (*temperature)(NvmlDevice, int, unsigned*) = nullptr;
  NvmlReturn (*power_usage)(NvmlDevice, unsigned*) = nullptr;
  NvmlReturn (*vbios_version)(NvmlDevice, char*, unsigned) = nullptr;  // optional
  NvmlReturn (*pci_info)(NvmlDevice, NvmlPciInfo*) = nullptr;          // optional
  bool initialised = false;

  ~Nvml() {
    if (initialised && shutdown) shutdown();
    if (lib) dlclose(lib);
  }
};

GpuMonitor::GpuMonitor() = default;
GpuMonitor::GpuMonitor(GpuMonitor&&) noexcept = default;
GpuMonitor& GpuMonitor::operator=(GpuMonitor&&) noexcept = default;
GpuMonitor::~GpuMonitor() = default;

GpuMonitor GpuMonitor::for_gl_context(const std::string& gl_vendor, const std::string& gl_renderer) {
  if (const char* lib = std::getenv("OITBENCH_NVML_LIBRARY"); lib && *lib) return open_library(lib, gl_renderer);
  if (gl_vendor.find("NVIDIA") == std::string::npos) {
    GpuMonitor m;
    m.why_ = "GL_VENDOR '" + gl_vendor + "' is not NVIDIA's: no NVML";
    return m;
  }
  return open_library("libnvidia-ml.so.1", gl_renderer);
}

GpuMonitor GpuMonitor::open_library(const std::string& path, const std::string& gl_renderer) {
  GpuMonitor m;
  auto n = std::make_unique<Nvml>();
  n->lib = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!n->lib) {
    const char* err = dlerror();
    m.why_ = "cannot load " + path + (err ? std::string(": ") + err : "");
    return m;
  }
  const char* missing = nullptr;
  if (!load(n->lib, "nvmlInit_v2", n->init)) missing = "nvmlInit_v2";
  if (!missing && !load(n->lib, "nvmlShutdown", n->shutdown)) missing = "nvmlShutdown";
  if (!missing && !load(n->lib, "nvmlSystemGetDriverVersion", n->driver_version))
    missing = "nvmlSystemGetDriverVersion";
  if (!missing && !load(n->lib, "nvmlDeviceGetCount_v2", n->device_count)) missing = "nvmlDeviceGetCount_v2";
  if (!missing && !load(n->lib, "nvmlDeviceGetHandleByIndex_v2", n->device_by_index))
    missing = "nvmlDeviceGetHandleByIndex_v2";
  if (!missing && !load(n->lib, "nvmlDeviceGetName", n->device_name)) missing = "nvmlDeviceGetName";
  if (!missing && !load(n->lib, "nvmlDeviceGetClockInfo", n->clock_info)) missing = "nvmlDeviceGetClockInfo";
  if (!missing && !load(n->lib, "nvmlDeviceGetTemperature", n->temperature)) missing = "nvmlDeviceGetTemperature";
  if (!missing && !load(n->lib, "nvmlDeviceGetPowerUsage", n->power_usage)) missing = "nvmlDeviceGetPowerUsage";
  if (missing) {
    m.why_ = path + " has no " + missing;
    return m;
  }
  if (NvmlReturn r = n->init(); r != kNvmlSuccess) {
    m.why_ = "nvmlInit_v2 failed (NVML error " + std::to_string(r) + ")";
    return m;
  }
  n->initialised = true;
  unsigned count = 0;
  if (n->device_count(&count) != kNvmlSuccess || count == 0) {
    m.why_ = "NVML lists no device";
    return m;
  }
  // The GL context's GPU: the first device whose NVML name appears in GL_RENDERER ("NVIDIA H200" in
  // "NVIDIA H200/PCIe/SSE2"), else device 0.
  std::string first_name;
  for (unsigned i = 0; i < count; ++i) {
    NvmlDevice d = nullptr;
    if (n->device_by_index(i, &d) != kNvmlSuccess) continue;
    char name[kNameBuffer] = {};
    std::string nm = n->device_name(d, name, kNameBuffer) == kNvmlSuccess ? name : "";
    if (!n->device) {
      n->device = d;
      first_name = nm;
    }
    if (!nm.empty() && gl_renderer.find(nm) != std::string::npos) {
      n->device = d;
      first_name = nm;
      break;
    }
  }
  if (!n->device) {
    m.why_ = "NVML gives no device handle";
    return m;
  }
  char version[kVersionBuffer] = {};
  if (n->driver_version(version, kVersionBuffer) == kNvmlSuccess) m.driver_version_ = version;
  m.device_name_ = first_name;
  m.read_identity(*n);
  m.nvml_ = std::move(n);
  return m;
}

void GpuMonitor::read_identity(Nvml& n) {
  if (load(n.lib, "nvmlDeviceGetVbiosVersion", n.vbios_version)) {
    char version[kVersionBuffer] = {};
    if (n.vbios_version(n.device, version, kVersionBuffer) == kNvmlSuccess) vbios_version_ = version;
  }
  if (load(n.lib, "nvmlDeviceGetPciInfo_v3", n.pci_info)) {
    NvmlPciInfo pci{};
    if (n.pci_info(n.device, &pci) == kNvmlSuccess && pci.pci_device_id != 0)
      pci_id_ = pci_id_text(pci.pci_device_id & 0xffffu, pci.pci_device_id >> 16);
  }
}

GpuIdentity gpu_identity(const GpuMonitor& gpu, const std::string& pci_bus, const std::string& sysfs) {
  GpuIdentity id{gpu.pci_id(), gpu.vbios_version()};
  if (!is_pci_address(pci_bus)) return id;
  const std::string dir = sysfs + "/bus/pci/devices/" + pci_bus + "/";
  if (id.pci_id.empty()) {
    const std::string vendor = first_line(dir + "vendor"), device = first_line(dir + "device");
    char* end_v = nullptr;
    char* end_d = nullptr;
    const unsigned long v = std::strtoul(vendor.c_str(), &end_v, 16), d = std::strtoul(device.c_str(), &end_d, 16);
    if (!vendor.empty() && !device.empty() && *end_v == '\0' && *end_d == '\0')
      id.pci_id = pci_id_text(static_cast<unsigned>(v), static_cast<unsigned>(d));
  }
  if (id.vbios_version.empty()) id.vbios_version = first_line(dir + "vbios_version");  // amdgpu's
  return id;
}

GpuReading GpuMonitor::read() const {
  GpuReading r;
  if (!nvml_) return r;
  unsigned v = 0;
  if (nvml_->clock_info(nvml_->device, kNvmlClockSm, &v) == kNvmlSuccess) r.sm_clock_mhz = v;
  if (nvml_->clock_info(nvml_->device, kNvmlClockMem, &v) == kNvmlSuccess) r.mem_clock_mhz = v;
  if (nvml_->temperature(nvml_->device, kNvmlTemperatureGpu, &v) == kNvmlSuccess) r.temperature_c = v;
  if (nvml_->power_usage(nvml_->device, &v) == kNvmlSuccess) r.power_w = v / 1000.0;
  return r;
}

std::map<std::string, std::string> gpu_state_columns(const GpuReading& start, const GpuReading& end) {
  return {{"gpu_sm_clock_start_mhz", cell(start.sm_clock_mhz)},
          {"gpu_sm_clock_end_mhz", cell(end.sm_clock_mhz)},
          {"gpu_mem_clock_start_mhz", cell(start.mem_clock_mhz)},
          {"gpu_mem_clock_end_mhz", cell(end.mem_clock_mhz)},
          {"gpu_temp_start_c", cell(start.temperature_c)},
          {"gpu_temp_end_c", cell(end.temperature_c)},
          {"gpu_power_start_w", cell(start.power_w)},
          {"gpu_power_end_w", cell(end.power_w)}};
}

std::string clock_change_note(const GpuReading& start, const GpuReading& end, double threshold) {
  if (!start.sm_clock_mhz || !end.sm_clock_mhz || *start.sm_clock_mhz == 0) return "";
  const double a = *start.sm_clock_mhz, b = *end.sm_clock_mhz;
  if (std::fabs(b - a) <= threshold * a) return "";
  return "gpu clocks changed during the case group: SM " + std::to_string(*start.sm_clock_mhz) + " -> " +
         std::to_string(*end.sm_clock_mhz) + " MHz";
}

}  // namespace oitbench
