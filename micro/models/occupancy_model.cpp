#include "models/occupancy_model.hpp"

#include <algorithm>

namespace oitbench {

namespace {
constexpr int kWarp = 32;
constexpr int kBaseRegisters = 8;    // the shader's own registers besides the array
constexpr int kRegisterGranule = 8;  // registers are allocated per thread in units of 8
}  // namespace

const std::vector<GpuBudget>& gpu_budgets() {
  // Public per-SM(X) figures: CUDA occupancy tables / whitepapers (Kepler GK104/GK110, Pascal GP104, Hopper GH100).
  static const std::vector<GpuBudget> table = {
      {"gtx670", "GTX 670", 65536, 2048, 63, 48 * 1024},        // GK104: 63 registers per thread
      {"gtx-titan", "GTX TITAN", 65536, 2048, 255, 48 * 1024},  // GK110
      {"gtx1080", "GTX 1080", 65536, 2048, 255, 48 * 1024},     // GP104: 48 KiB L1/tex per SM
      {"h100", "H100", 65536, 2048, 255, 256 * 1024},           // GH100: 256 KiB L1/shared per SM
      {"h200", "H200", 65536, 2048, 255, 256 * 1024},
  };
  return table;
}

std::optional<GpuBudget> find_budget(const std::string& model_gpu, const std::string& renderer) {
  for (const auto& g : gpu_budgets()) {
    if (model_gpu == g.key) return g;
    if (model_gpu == "auto" && renderer.find(g.match) != std::string::npos) return g;
  }
  return std::nullopt;
}

OccupancyPrediction predict_occupancy(const GpuBudget& gpu, int size, bool indexed_dynamically) {
  OccupancyPrediction p;
  const int array_registers = 4 * size;
  int threads = gpu.max_threads_per_sm;
  if (!indexed_dynamically && kBaseRegisters + array_registers <= gpu.max_registers_per_thread) {
    int regs = (kBaseRegisters + array_registers + kRegisterGranule - 1) / kRegisterGranule * kRegisterGranule;
    threads = std::min(threads, gpu.registers_per_sm / regs / kWarp * kWarp);
    p.in_registers = true;
  } else {
    const int bytes = 16 * size;  // the array in local memory, kept resident in L1
    threads = std::min(threads, gpu.local_cache_bytes / bytes / kWarp * kWarp);
  }
  p.threads_per_sm = std::max(threads, kWarp);  // at least one warp always runs
  p.occupancy = static_cast<double>(p.threads_per_sm) / gpu.max_threads_per_sm;
  return p;
}

}  // namespace oitbench
