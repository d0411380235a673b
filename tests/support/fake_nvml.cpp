// A stand-in for libnvidia-ml.so.1 with the entry points core/gpu_state.cpp loads, so the tests can run the
// NVML path on a machine without NVIDIA's driver. Two devices ("NVIDIA A100-SXM4-80GB", "NVIDIA H200"); the
// SM clock alternates 1980 and 1410 MHz from one reading to the next, so a case group sees it change. The H200
// is PCI ID 10de:2335 with VBIOS 96.00.99.00.01.
#include <cstring>

namespace {
int sm_readings = 0;
const char* const kNames[] = {"NVIDIA A100-SXM4-80GB", "NVIDIA H200"};
int copy(const char* s, char* out, unsigned length) {
  if (std::strlen(s) + 1 > length) return 7;  // NVML_ERROR_INSUFFICIENT_SIZE
  std::strcpy(out, s);
  return 0;
}
}  // namespace

extern "C" {
int nvmlInit_v2() {
  sm_readings = 0;
  return 0;
}
int nvmlShutdown() { return 0; }
int nvmlSystemGetDriverVersion(char* version, unsigned length) { return copy("550.54.15", version, length); }
int nvmlDeviceGetCount_v2(unsigned* count) {
  *count = 2;
  return 0;
}
int nvmlDeviceGetHandleByIndex_v2(unsigned index, void** device) {
  if (index > 1) return 2;  // NVML_ERROR_INVALID_ARGUMENT
  *device = const_cast<char*>(kNames[index]);
  return 0;
}
int nvmlDeviceGetName(void* device, char* name, unsigned length) {
  return copy(static_cast<const char*>(device), name, length);
}
int nvmlDeviceGetClockInfo(void*, int type, unsigned* clock) {
  if (type == 1) {  // NVML_CLOCK_SM
    *clock = sm_readings++ % 2 == 0 ? 1980 : 1410;
    return 0;
  }
  if (type == 2) {  // NVML_CLOCK_MEM
    *clock = 2619;
    return 0;
  }
  return 3;  // NVML_ERROR_NOT_SUPPORTED
}
int nvmlDeviceGetTemperature(void*, int sensor, unsigned* temp) {
  if (sensor != 0) return 3;
  *temp = 45;
  return 0;
}
int nvmlDeviceGetPowerUsage(void*, unsigned* milliwatts) {
  *milliwatts = 350125;
  return 0;
}
int nvmlDeviceGetVbiosVersion(void* device, char* version, unsigned length) {
  return copy(device == kNames[1] ? "96.00.99.00.01" : "92.00.45.00.06", version, length);
}
// nvmlPciInfo_t: busIdLegacy[16], domain, bus, device, pciDeviceId (device << 16 | vendor), pciSubSystemId, busId[32].
struct PciInfo {
  char bus_id_legacy[16];
  unsigned domain, bus, device, pci_device_id, pci_subsystem_id;
  char bus_id[32];
};
int nvmlDeviceGetPciInfo_v3(void* device, PciInfo* pci) {
  *pci = PciInfo{};
  pci->pci_device_id = device == kNames[1] ? 0x233510deu : 0x20b210deu;
  return 0;
}
}
