#pragma once
// A small, documented occupancy model (docs/experiments/occupancy.md): how many threads per SM (NVIDIA) or CU
// (AMD) fit when each thread holds `vec4 myArray[SIZE]`, from a few GPUs' public per-SM / per-CU budgets.
#include <optional>
#include <string>
#include <vector>

namespace oitbench {

struct GpuBudget {
  std::string key;                   // value of the experiment's model_gpu parameter
  std::vector<std::string> matches;  // GL_RENDERER names that select it under model_gpu=auto (whole words)
  std::string chip;                  // "GH100 (compute capability 9.0)", "Navi 31 (gfx1100)"
  // Per SM (NVIDIA) or per CU of two SIMD32s (AMD, counted in wave32 lanes):
  int registers_per_sm;  // 32-bit registers in the register file(s)
  int max_threads_per_sm;
  int max_registers_per_thread;
  int local_cache_bytes;  // the L1 (NVIDIA) or vector L0 (AMD) that caches local (spilled/indexed) memory
  // How registers are allocated: per thread in multiples of `register_granule`, and each warp or wave
  // lives in one of `register_partitions` equal slices of the file (SM sub-partitions; SIMDs of a CU).
  int register_granule = 8;
  int register_partitions = 4;
};

const std::vector<GpuBudget>& gpu_budgets();
// `model_gpu` a key of the table: that budget. "auto": the first budget one of whose `matches` appears
// in `gl_renderer` as a whole word (not followed or preceded by a letter or digit: "A100" does not
// select "RTX A1000"). Otherwise none (the row says model_gpu_used=unknown).
std::optional<GpuBudget> find_budget(const std::string& model_gpu, const std::string& gl_renderer);

struct OccupancyPrediction {
  int registers_per_thread = 0;  // allocated (rounded up to the granule); 0 when the array is in local memory
  int threads_per_sm = 0;
  double occupancy = 0;  // threads_per_sm / max_threads_per_sm
  bool in_registers = false;
};

// Registers a thread needs besides the array (the model's constant overhead).
inline constexpr int kOccupancyBaseRegisters = 8;

// `indexed_dynamically`: the array lives in local memory (bounded by the L1 budget); otherwise it
// is held in registers while it fits in max_registers_per_thread (bounded by the register file):
//   registers = roundup(8 + 4 * SIZE, granule)
//   warps     = floor(registers_per_sm / partitions / (registers * 32)) * partitions
//   threads   = min(max_threads_per_sm, 32 * warps)
// and in local memory: threads = min(max_threads_per_sm, 32 * floor(local_cache_bytes / (16 * SIZE) / 32)).
// At least one warp always runs.
OccupancyPrediction predict_occupancy(const GpuBudget& gpu, int size, bool indexed_dynamically);

}  // namespace oitbench
