#pragma once
// A small, documented occupancy model (README, "occupancy"): how many threads per SM fit when
// each thread holds `vec4 myArray[SIZE]`, from a few GPUs' public per-SM budgets.
#include <optional>
#include <string>
#include <vector>

namespace oitbench {

struct GpuBudget {
  std::string key;       // value of the experiment's model_gpu parameter
  std::string match;     // substring of GL_RENDERER that selects it under model_gpu=auto
  int registers_per_sm;  // 32-bit registers
  int max_threads_per_sm;
  int max_registers_per_thread;
  int local_cache_bytes;  // L1 that caches local (spilled/indexed) memory
};

const std::vector<GpuBudget>& gpu_budgets();
std::optional<GpuBudget> find_budget(const std::string& model_gpu, const std::string& gl_renderer);

struct OccupancyPrediction {
  int threads_per_sm = 0;
  double occupancy = 0;  // threads_per_sm / max_threads_per_sm
  bool in_registers = false;
};

// `indexed_dynamically`: the array lives in local memory (bounded by the L1 budget); otherwise it
// is held in registers while it fits in max_registers_per_thread (bounded by the register file).
OccupancyPrediction predict_occupancy(const GpuBudget& gpu, int size, bool indexed_dynamically);

}  // namespace oitbench
