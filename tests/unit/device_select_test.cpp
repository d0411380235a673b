// --device for --backend egl-device: the choice over device descriptions and the environment
// (backends/device_select.hpp), table-driven, without a GPU.
#include "backends/device_select.hpp"

#include <gtest/gtest.h>

namespace oitbench {
namespace {

using Env = std::map<std::string, std::string>;

// Two NVIDIA GPUs (CUDA 0 and 1) and Mesa's software device without a DRM node.
std::vector<DeviceDescription> machine() {
  return {{0, 0, "/dev/dri/card1", "/dev/dri/renderD128", "0000:01:00.0"},
          {1, 1, "/dev/dri/card2", "/dev/dri/renderD129", "0000:41:00.0"},
          {2, -1, "", "", ""}};
}

struct Case {
  const char* spec;
  Env env;
  int index;         // -1: an error
  const char* text;  // in the rule (or in the error when index is -1)
};

TEST(DeviceSelect, ChoosesByIndexCudaDrmAndEnvironment) {
  const std::vector<Case> cases = {
      {"0", {}, 0, "index 0"},
      {"2", {}, 2, "index 2"},
      {"cuda:1", {}, 1, "cuda:1"},
      {"cuda:0", {{"CUDA_VISIBLE_DEVICES", "1"}}, 0, "cuda:0"},
      {"drm:/dev/dri/renderD129", {}, 1, "drm:/dev/dri/renderD129"},
      {"drm:/dev/dri/card1", {}, 0, "drm:/dev/dri/card1"},
      {"auto", {}, 0, "no scheduler variable -> index 0"},
      {"auto", {{"CUDA_VISIBLE_DEVICES", "3"}}, 0, "CUDA_VISIBLE_DEVICES=3 -> cuda:0"},
      {"auto", {{"CUDA_VISIBLE_DEVICES", "GPU-8f2c1a7e-1234-5678-9abc-def012345678,GPU-1"}}, 0, "-> cuda:0"},
      {"auto", {{"CUDA_VISIBLE_DEVICES", "1"}, {"SLURM_STEP_GPUS", "1"}}, 0, "CUDA_VISIBLE_DEVICES"},
      {"auto", {{"SLURM_STEP_GPUS", "1,0"}}, 1, "SLURM_STEP_GPUS=1,0 -> cuda:1"},
      {"auto", {{"SLURM_JOB_GPUS", "1"}, {"GPU_DEVICE_ORDINAL", "0"}}, 1, "SLURM_JOB_GPUS=1 -> cuda:1"},
      {"auto", {{"GPU_DEVICE_ORDINAL", " 1 "}}, 1, "GPU_DEVICE_ORDINAL"},
      {"auto", {{"SLURM_STEP_GPUS", ""}, {"SLURM_JOB_GPUS", "0"}}, 0, "SLURM_JOB_GPUS=0"},
  };
  for (const auto& c : cases) {
    auto got = choose_device(c.spec, machine(), c.env);
    EXPECT_EQ(got.error, "") << c.spec;
    EXPECT_EQ(got.index, c.index) << c.spec;
    EXPECT_NE(got.rule.find(c.text), std::string::npos) << c.spec << ": " << got.rule;
  }
}

TEST(DeviceSelect, RefusesWhatNamesNoDevice) {
  const std::vector<Case> cases = {
      {"3", {}, -1, "index 3 is out of range (3 device(s))"},
      {"cuda:x", {}, -1, "cuda: needs a CUDA ordinal"},
      {"cuda:", {}, -1, "cuda: needs a CUDA ordinal"},
      {"cuda:2", {}, -1, "no EGL device has CUDA ordinal 2"},
      {"drm:", {}, -1, "drm: needs a DRM node"},
      {"drm:/dev/dri/renderD200", {}, -1, "no EGL device has the DRM node /dev/dri/renderD200"},
      {"-1", {}, -1, "unknown device '-1'; valid: N (an index), cuda:N, drm:PATH, auto"},
      {"gpu0", {}, -1, "unknown device 'gpu0'"},
      {"", {}, -1, "unknown device ''"},
      {"auto", {{"CUDA_VISIBLE_DEVICES", ""}}, -1, "makes no device visible"},
      {"auto", {{"CUDA_VISIBLE_DEVICES", "NoDevFiles"}}, -1, "makes no device visible"},
      {"auto", {{"SLURM_STEP_GPUS", "(null)"}}, -1, "the first entry is not a GPU index"},
      {"auto", {{"SLURM_JOB_GPUS", "5"}}, -1, "no EGL device has CUDA ordinal 5"},
  };
  for (const auto& c : cases) {
    auto got = choose_device(c.spec, machine(), c.env);
    EXPECT_EQ(got.index, -1) << c.spec;
    EXPECT_NE(got.error.find(c.text), std::string::npos) << c.spec << ": " << got.error;
  }
}

TEST(DeviceSelect, WithoutCudaAttributesAutoUnderAScheduler) {
  // Mesa-only machines (no EGL_NV_device_cuda): auto under CUDA_VISIBLE_DEVICES names no device.
  std::vector<DeviceDescription> mesa = {{0, -1, "/dev/dri/card0", "/dev/dri/renderD128", "0000:00:02.0"}};
  EXPECT_EQ(choose_device("auto", mesa, {{"CUDA_VISIBLE_DEVICES", "0"}}).index, -1);
  EXPECT_EQ(choose_device("auto", mesa, {}).index, 0);
  EXPECT_EQ(choose_device("auto", {}, {}).error, "there are no EGL devices");
}

TEST(DeviceSelect, DescribesTheDevicesForErrors) {
  EXPECT_EQ(describe_devices(machine()),
            "0: cuda:0, /dev/dri/card1, /dev/dri/renderD128, 0000:01:00.0; "
            "1: cuda:1, /dev/dri/card2, /dev/dri/renderD129, 0000:41:00.0; 2: (no DRM node)");
  EXPECT_EQ(describe_devices({}), "no EGL devices");
}

}  // namespace
}  // namespace oitbench
