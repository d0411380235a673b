#pragma once
// The GPU's state where its driver lets a program read it: NVIDIA's management library (NVML), loaded
// at run time with dlopen("libnvidia-ml.so.1"), so nothing is needed at build time and a machine without it
// (llvmpipe, AMD, no driver) simply records nothing. The runner reads the driver version once and the SM
// and memory clocks, the temperature and the power at the start and end of each case group
// (docs/measurement.md, "GPU state").
#include <map>
#include <memory>
#include <optional>
#include <string>

namespace oitbench {

struct GpuReading {
  std::optional<unsigned> sm_clock_mhz, mem_clock_mhz, temperature_c;
  std::optional<double> power_w;
};

class GpuMonitor {
 public:
  // NVML for the GL context's GPU, only when GL_VENDOR is NVIDIA's (a software renderer on a machine that
  // also has an NVIDIA GPU must not record that GPU's clocks) and libnvidia-ml.so.1 loads and initialises.
  // Otherwise an inactive monitor: every reading empty, why_inactive() says why. Never throws.
  // $OITBENCH_NVML_LIBRARY names another library to load whatever the vendor (the tests' fake NVML).
  static GpuMonitor for_gl_context(const std::string& gl_vendor, const std::string& gl_renderer);
  // NVML from the library at `path` (the tests load a fake one); the device whose name appears in
  // `gl_renderer`, else the first.
  static GpuMonitor open_library(const std::string& path, const std::string& gl_renderer);

  GpuMonitor();
  GpuMonitor(GpuMonitor&&) noexcept;
  GpuMonitor& operator=(GpuMonitor&&) noexcept;
  ~GpuMonitor();  // nvmlShutdown, dlclose

  bool active() const { return nvml_ != nullptr; }
  const std::string& why_inactive() const { return why_; }
  const std::string& driver_version() const { return driver_version_; }
  const std::string& device_name() const { return device_name_; }
  // The device's VBIOS version (nvmlDeviceGetVbiosVersion) and PCI ID ("10de:2335", vendor:device, from
  // nvmlDeviceGetPciInfo_v3), where the library has those entry points; empty otherwise.
  const std::string& vbios_version() const { return vbios_version_; }
  const std::string& pci_id() const { return pci_id_; }
  // What can be read now; a value the device does not report stays empty.
  GpuReading read() const;

 private:
  struct Nvml;
  void read_identity(Nvml& n);
  std::unique_ptr<Nvml> nvml_;
  std::string why_, driver_version_, device_name_, vbios_version_, pci_id_;
};

// A run's GPU identity (the gpu_pci_id and gpu_vbios_version columns): NVML's where the monitor has it, else
// sysfs's for the PCI bus the context's device is on (device_pci_bus: `sysfs`/bus/pci/devices/BUS/vendor,
// device, and amdgpu's vbios_version). Empty what neither says (llvmpipe, no bus known). Never throws.
struct GpuIdentity {
  std::string pci_id, vbios_version;
};
GpuIdentity gpu_identity(const GpuMonitor& gpu, const std::string& pci_bus, const std::string& sysfs = "/sys");

// The columns of one case group's readings (gpu_sm_clock_start_mhz, ..., gpu_power_end_w); a value not
// read is an empty cell.
std::map<std::string, std::string> gpu_state_columns(const GpuReading& start, const GpuReading& end);

// "gpu clocks changed during the case group: SM 1980 -> 1410 MHz" when the SM clock at the end differs from
// the one at the start by more than `threshold` of it; empty when it did not or either reading is missing.
std::string clock_change_note(const GpuReading& start, const GpuReading& end, double threshold = 0.05);

}  // namespace oitbench
