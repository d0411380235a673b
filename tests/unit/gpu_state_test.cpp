// GPU state through NVML: the path without NVML (this machine, llvmpipe) records nothing and fails nothing;
// the NVML path runs against a fake libnvidia-ml (tests/support/fake_nvml.cpp); the clock-change note.
#include "core/gpu_state.hpp"

#include <dlfcn.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <string>

namespace oitbench {

TEST(GpuState, ASoftwareRendererNeverOpensNvml) {
  auto m = GpuMonitor::for_gl_context("Mesa", "llvmpipe (LLVM 15.0.6, 256 bits)");
  EXPECT_FALSE(m.active());
  EXPECT_NE(m.why_inactive().find("not NVIDIA's"), std::string::npos) << m.why_inactive();
  EXPECT_EQ(m.driver_version(), "");
  auto r = m.read();
  EXPECT_FALSE(r.sm_clock_mhz || r.mem_clock_mhz || r.temperature_c || r.power_w);
  for (const auto& [k, v] : gpu_state_columns(r, r)) EXPECT_EQ(v, "") << k;
  EXPECT_EQ(clock_change_note(r, r), "");
}

TEST(GpuState, NoLibraryIsAnInactiveMonitorNotAnError) {
  auto m = GpuMonitor::open_library("/nonexistent/libnvidia-ml.so.1", "NVIDIA H200/PCIe/SSE2");
  EXPECT_FALSE(m.active());
  EXPECT_NE(m.why_inactive().find("cannot load /nonexistent/libnvidia-ml.so.1"), std::string::npos) << m.why_inactive();
  // An NVIDIA GL_VENDOR on a machine without NVIDIA's driver (as here): the same, quietly.
  if (void* lib = dlopen("libnvidia-ml.so.1", RTLD_NOW | RTLD_LOCAL)) {
    dlclose(lib);
    GTEST_SKIP() << "this machine has libnvidia-ml.so.1";
  }
  auto nv = GpuMonitor::for_gl_context("NVIDIA Corporation", "NVIDIA H200/PCIe/SSE2");
  EXPECT_FALSE(nv.active());
  EXPECT_NE(nv.why_inactive().find("libnvidia-ml.so.1"), std::string::npos) << nv.why_inactive();
}

TEST(GpuState, ALibraryWithoutTheEntryPointsIsNamed) {
  // libm loads but is no NVML.
  auto m = GpuMonitor::open_library("libm.so.6", "NVIDIA H200");
  EXPECT_FALSE(m.active());
  EXPECT_NE(m.why_inactive().find("has no nvmlInit_v2"), std::string::npos) << m.why_inactive();
}

TEST(GpuState, ReadsTheGlContextsDeviceThroughNvml) {
  auto m = GpuMonitor::open_library(FAKE_NVML_LIBRARY, "NVIDIA H200/PCIe/SSE2");
  ASSERT_TRUE(m.active()) << m.why_inactive();
  EXPECT_EQ(m.driver_version(), "550.54.15");
  EXPECT_EQ(m.device_name(), "NVIDIA H200");  // the second device, named in GL_RENDERER
  auto start = m.read(), end = m.read();
  EXPECT_EQ(start.sm_clock_mhz.value_or(0), 1980u);
  EXPECT_EQ(end.sm_clock_mhz.value_or(0), 1410u);
  EXPECT_EQ(start.mem_clock_mhz.value_or(0), 2619u);
  EXPECT_EQ(start.temperature_c.value_or(0), 45u);
  EXPECT_DOUBLE_EQ(start.power_w.value_or(0), 350.125);
  auto cols = gpu_state_columns(start, end);
  EXPECT_EQ(cols.at("gpu_sm_clock_start_mhz"), "1980");
  EXPECT_EQ(cols.at("gpu_sm_clock_end_mhz"), "1410");
  EXPECT_EQ(cols.at("gpu_mem_clock_end_mhz"), "2619");
  EXPECT_EQ(cols.at("gpu_temp_start_c"), "45");
  EXPECT_EQ(cols.at("gpu_power_end_w"), "350.1");
  EXPECT_EQ(clock_change_note(start, end), "gpu clocks changed during the case group: SM 1980 -> 1410 MHz");
  // A renderer no device is named in: the first device.
  auto other = GpuMonitor::open_library(FAKE_NVML_LIBRARY, "NVIDIA GeForce RTX 4090/PCIe/SSE2");
  ASSERT_TRUE(other.active());
  EXPECT_EQ(other.device_name(), "NVIDIA A100-SXM4-80GB");
  // The identity: NVML's PCI ID and VBIOS of the chosen device, before anything sysfs says.
  EXPECT_EQ(m.pci_id(), "10de:2335");
  EXPECT_EQ(m.vbios_version(), "96.00.99.00.01");
  EXPECT_EQ(other.pci_id(), "10de:20b2");
  const GpuIdentity id = gpu_identity(m, "0000:01:00.0", "/nonexistent");
  EXPECT_EQ(id.pci_id, "10de:2335");
  EXPECT_EQ(id.vbios_version, "96.00.99.00.01");
}

// Without NVML (AMD, Intel, egl-device on Mesa): sysfs's vendor, device and amdgpu's vbios_version for the
// context's PCI bus; nothing (and no failure) where the bus is unknown, not an address, or not there.
TEST(GpuState, TheIdentityComesFromSysfsWithoutNvml) {
  const std::string root = ::testing::TempDir() + "oitbench-sysfs-" + std::to_string(::getpid());
  const std::string dir = root + "/bus/pci/devices/0000:03:00.0";
  ASSERT_EQ(std::system(("mkdir -p '" + dir + "'").c_str()), 0);
  std::ofstream(dir + "/vendor") << "0x1002\n";
  std::ofstream(dir + "/device") << "0x73bf\n";
  std::ofstream(dir + "/vbios_version") << "113-D4120100-100\n";
  const GpuMonitor none;
  GpuIdentity id = gpu_identity(none, "0000:03:00.0", root);
  EXPECT_EQ(id.pci_id, "1002:73bf");
  EXPECT_EQ(id.vbios_version, "113-D4120100-100");
  for (const std::string bus : {"", "0000:04:00.0", "../../../etc", "0000:03:00.0/.."}) {
    id = gpu_identity(none, bus, root);
    EXPECT_EQ(id.pci_id, "") << bus;
    EXPECT_EQ(id.vbios_version, "") << bus;
  }
  std::ofstream(dir + "/device") << "not hex\n";  // a file that does not parse: no PCI ID, not a wrong one
  EXPECT_EQ(gpu_identity(none, "0000:03:00.0", root).pci_id, "");
  EXPECT_EQ(gpu_identity(GpuMonitor(), "", "/sys").pci_id, "");  // this machine's llvmpipe: nothing, no failure
  ASSERT_EQ(std::system(("rm -rf '" + root + "'").c_str()), 0);
}

TEST(GpuState, TheClockNoteNeedsAChangeOverFivePercent) {
  auto reading = [](unsigned sm) {
    GpuReading r;
    r.sm_clock_mhz = sm;
    return r;
  };
  EXPECT_EQ(clock_change_note(reading(1980), reading(1980)), "");
  EXPECT_EQ(clock_change_note(reading(2000), reading(1900)), "");  // exactly 5%
  EXPECT_EQ(clock_change_note(reading(2000), reading(2100)), "");
  EXPECT_EQ(clock_change_note(reading(2000), reading(1899)),
            "gpu clocks changed during the case group: SM 2000 -> 1899 MHz");
  EXPECT_EQ(clock_change_note(reading(1410), reading(1980)),
            "gpu clocks changed during the case group: SM 1410 -> 1980 MHz");  // boost after idle counts too
  EXPECT_EQ(clock_change_note(reading(1980), GpuReading{}), "");               // a missing reading says nothing
  EXPECT_EQ(clock_change_note(GpuReading{}, reading(1410)), "");
  EXPECT_EQ(clock_change_note(reading(1980), reading(1410), 0.5), "");  // the threshold is a parameter
}

}  // namespace oitbench
