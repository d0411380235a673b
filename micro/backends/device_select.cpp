#include "backends/device_select.hpp"

#include <cctype>
#include <cstdlib>

namespace oitbench {
namespace {

bool all_digits(const std::string& s) {
  if (s.empty() || s.size() > 6) return false;
  for (char c : s)
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  return true;
}

std::string first_entry(const std::string& list) {
  std::string e = list.substr(0, list.find(','));
  while (!e.empty() && std::isspace(static_cast<unsigned char>(e.back()))) e.pop_back();
  size_t start = 0;
  while (start < e.size() && std::isspace(static_cast<unsigned char>(e[start]))) ++start;
  return e.substr(start);
}

DeviceChoice by_cuda(int ordinal, const std::vector<DeviceDescription>& devices, std::string rule) {
  for (const auto& d : devices)
    if (d.cuda == ordinal) return {d.index, rule, ""};
  return {-1, rule,
          "no EGL device has CUDA ordinal " + std::to_string(ordinal) + " (EGL_CUDA_DEVICE_NV, NVIDIA's driver only)"};
}

DeviceChoice by_drm(const std::string& path, const std::vector<DeviceDescription>& devices) {
  if (path.empty()) return {-1, "", "drm: needs a DRM node, e.g. drm:/dev/dri/renderD128 or drm:/dev/dri/card0"};
  for (const auto& d : devices)
    if (d.drm_file == path || d.render_node == path) return {d.index, "drm:" + path, ""};
  return {-1, "drm:" + path, "no EGL device has the DRM node " + path};
}

DeviceChoice from_environment(const std::vector<DeviceDescription>& devices,
                              const std::map<std::string, std::string>& env) {
  auto cvd = env.find("CUDA_VISIBLE_DEVICES");
  if (cvd != env.end()) {
    std::string e = first_entry(cvd->second);
    std::string rule =
        "auto: CUDA_VISIBLE_DEVICES=" + cvd->second + " -> cuda:0 (CUDA renumbers the visible devices from 0)";
    if (all_digits(e) || e.rfind("GPU-", 0) == 0 || e.rfind("MIG-", 0) == 0) return by_cuda(0, devices, rule);
    return {-1, rule, "CUDA_VISIBLE_DEVICES=" + cvd->second + " makes no device visible (first entry '" + e + "')"};
  }
  for (const char* name : {"SLURM_STEP_GPUS", "SLURM_JOB_GPUS", "GPU_DEVICE_ORDINAL"}) {
    auto it = env.find(name);
    if (it == env.end() || it->second.empty()) continue;
    std::string e = first_entry(it->second);
    if (!all_digits(e)) return {-1, "", std::string(name) + "=" + it->second + ": the first entry is not a GPU index"};
    int n = std::stoi(e);
    return by_cuda(n, devices,
                   "auto: " + std::string(name) + "=" + it->second + " -> cuda:" + e + " (the physical index)");
  }
  if (devices.empty()) return {-1, "auto: no scheduler variable -> index 0", "there are no EGL devices"};
  return {devices.front().index, "auto: no scheduler variable -> index 0", ""};
}

}  // namespace

DeviceChoice choose_device(const std::string& spec, const std::vector<DeviceDescription>& devices,
                           const std::map<std::string, std::string>& env) {
  if (spec == "auto") return from_environment(devices, env);
  if (all_digits(spec)) {
    int n = std::stoi(spec);
    if (n < static_cast<int>(devices.size())) return {n, "index " + spec, ""};
    return {-1, "", "index " + spec + " is out of range (" + std::to_string(devices.size()) + " device(s))"};
  }
  if (spec.rfind("cuda:", 0) == 0) {
    std::string n = spec.substr(5);
    if (!all_digits(n)) return {-1, "", "cuda: needs a CUDA ordinal (a whole number), got '" + n + "'"};
    return by_cuda(std::stoi(n), devices, "cuda:" + n);
  }
  if (spec.rfind("drm:", 0) == 0) return by_drm(spec.substr(4), devices);
  return {-1, "", "unknown device '" + spec + "'; valid: N (an index), cuda:N, drm:PATH, auto"};
}

std::string describe_devices(const std::vector<DeviceDescription>& devices) {
  if (devices.empty()) return "no EGL devices";
  std::string out;
  for (const auto& d : devices) {
    std::string parts;
    auto add = [&parts](const std::string& s) {
      if (!s.empty()) parts += (parts.empty() ? "" : ", ") + s;
    };
    if (d.cuda >= 0) add("cuda:" + std::to_string(d.cuda));
    add(d.drm_file);
    add(d.render_node);
    add(d.pci_bus);
    out += (out.empty() ? "" : "; ") + std::to_string(d.index) + ": " + (parts.empty() ? "(no DRM node)" : parts);
  }
  return out;
}

std::map<std::string, std::string> device_environment() {
  std::map<std::string, std::string> env;
  for (const char* name : {"CUDA_VISIBLE_DEVICES", "SLURM_STEP_GPUS", "SLURM_JOB_GPUS", "GPU_DEVICE_ORDINAL"})
    if (const char* v = std::getenv(name)) env[name] = v;
  return env;
}

}  // namespace oitbench
