#pragma once
// Which EGL device `--device` names (--backend egl-device), decided over plain descriptions of the
// devices and the environment so that it is tested without a GPU; egl_backend.cpp fills the list.
#include <map>
#include <string>
#include <vector>

namespace oitbench {

struct DeviceDescription {
  int index = 0;
  int cuda = -1;            // EGL_CUDA_DEVICE_NV where EGL_NV_device_cuda is present, else -1
  std::string drm_file;     // EGL_DRM_DEVICE_FILE_EXT, e.g. /dev/dri/card0
  std::string render_node;  // EGL_DRM_RENDER_NODE_FILE_EXT, e.g. /dev/dri/renderD128
  std::string pci_bus;      // /sys/class/drm/<node>/device's name, e.g. 0000:01:00.0
};

struct DeviceChoice {
  int index = -1;     // into the device list; -1 with `error` set
  std::string rule;   // how it was chosen, in words ("CUDA_VISIBLE_DEVICES=3 -> cuda:0 ...")
  std::string error;  // why nothing fits (the caller adds the list of devices)
};

// `spec`: N (an index), cuda:N, drm:PATH (the DRM card or render node) or auto. auto takes the first
// entry of CUDA_VISIBLE_DEVICES (any entry -> cuda:0: the process sees its devices renumbered from 0),
// else of SLURM_STEP_GPUS, SLURM_JOB_GPUS, GPU_DEVICE_ORDINAL (physical index N -> cuda:N), else index 0.
DeviceChoice choose_device(const std::string& spec, const std::vector<DeviceDescription>& devices,
                           const std::map<std::string, std::string>& env);

// "0: cuda:0, /dev/dri/card1, /dev/dri/renderD128, 0000:01:00.0; 1: (no DRM node)" for error messages.
std::string describe_devices(const std::vector<DeviceDescription>& devices);

// The variables choose_device reads, from the process environment.
std::map<std::string, std::string> device_environment();

}  // namespace oitbench
