#include "models/occupancy_model.hpp"

#include <algorithm>
#include <cctype>

namespace oitbench {

namespace {
constexpr int kWarp = 32;  // NVIDIA warps; AMD waves counted as wave32 (see the AMD entries)
constexpr int kKiB = 1024;

bool is_word_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0; }

// `word` occurs in `text` with no letter or digit right before or after it.
bool contains_word(const std::string& text, const std::string& word) {
  for (size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1)) {
    bool starts = at == 0 || !is_word_char(text[at - 1]);
    size_t end = at + word.size();
    bool ends = end == text.size() || !is_word_char(text[end]);
    if (starts && ends) return true;
  }
  return false;
}
}  // namespace

// Sources.
// NVIDIA, per SM: registers per SM, resident threads per SM and registers per thread from the CUDA C++
//   Programming Guide, "Technical Specifications per Compute Capability" (the guide says 255 registers per
//   thread from cc 3.5 on; the occupancy calculator's cudaOccRegAllocationMaxPerThread says 256 from cc 7.0:
//   the model keeps 255, what ptxas allocates at most). Register allocation from the CUDA occupancy
//   calculator, cuda_occupancy.h: 256 registers per warp (8 per thread, cudaOccRegAllocationGranularity),
//   4 register sub-partitions per SM (cudaOccSubPartitionsPerMultiprocessor; 2 only on cc 6.0, which is
//   not in the table). L1: the largest L1 share of each SM's L1 (with the smallest shared-memory
//   carve-out), from the architecture tuning guides and whitepapers.
// AMD, per CU (two SIMD32s; RDNA pairs two CUs in a WGP): the VGPR file of one SIMD times 2, in 32-bit
//   registers of wave32 lanes (RDNA 2: 1024 VGPRs per lane = 128 KiB per SIMD; Navi 31: 1536 = 192 KiB, the
//   RDNA 3 whitepaper's 50% larger file); waves per SIMD, VGPR allocation granule (wave32) and total VGPRs
//   from LLVM's AMDGPU backend (AMDGPUBaseInfo.cpp: getMaxWavesPerEU = 16 on gfx10.3 and later,
//   getVGPRAllocGranule = 16 on gfx10.3 and 24 with the 1.5x VGPR file, getTotalNumVGPRs 1024 / 1536),
//   256 addressable VGPRs per thread (RDNA ISA guides: v0-v255). So resident threads per CU =
//   2 SIMDs x 16 waves x 32 lanes = 1024. Pixel shaders may run as wave64 (the driver chooses): a wave
//   then holds 64 threads, the register-bound thread count is the same, and the thread cap would be 2048;
//   the model counts wave32. The local-memory budget is the CU's vector L0 cache (16 KiB on RDNA 2, 32 KiB
//   on RDNA 3 per the RDNA 3 whitepaper; scratch also goes through the 128/256 KiB L1 shared by a shader
//   array, which the model ignores): less sure than the register figures.
const std::vector<GpuBudget>& gpu_budgets() {
  static const std::vector<GpuBudget> table = {
      // cc 3.0: 63 registers per thread; 48 KiB L1 (16/48 KiB split with shared memory).
      {"gtx670", {"GTX 670"}, "GK104 (compute capability 3.0)", 65536, 2048, 63, 48 * kKiB, 8, 4},
      {"gtx-titan", {"GTX TITAN"}, "GK110 (compute capability 3.5)", 65536, 2048, 255, 48 * kKiB, 8, 4},
      // cc 6.1: 48 KiB unified L1/texture per SM (Pascal tuning guide).
      {"gtx1080", {"GTX 1080"}, "GP104 (compute capability 6.1)", 65536, 2048, 255, 48 * kKiB, 8, 4},
      // cc 7.5: 1024 threads (32 warps) per SM; 96 KiB L1/shared, L1 64 KiB with 32 KiB shared (Turing tuning
      // guide).
      {"rtx2080ti", {"RTX 2080 Ti", "TITAN RTX"}, "TU102 (compute capability 7.5)", 65536, 1024, 255, 64 * kKiB, 8, 4},
      // cc 8.0: 2048 threads per SM; 192 KiB L1/shared per SM, shared up to 164 KiB (A100 whitepaper).
      {"a100", {"A100"}, "GA100 (compute capability 8.0)", 65536, 2048, 255, 192 * kKiB, 8, 4},
      // cc 8.6: 1536 threads (48 warps) per SM; 128 KiB L1/shared per SM (GA102 whitepaper).
      {"rtx3090", {"RTX 3090", "RTX 3080"}, "GA102 (compute capability 8.6)", 65536, 1536, 255, 128 * kKiB, 8, 4},
      // cc 8.9: 1536 threads per SM; 128 KiB L1/shared per SM (Ada whitepaper, AD102).
      {"rtx4090", {"RTX 4090"}, "AD102 (compute capability 8.9)", 65536, 1536, 255, 128 * kKiB, 8, 4},
      // cc 9.0: 2048 threads per SM; 256 KiB L1/shared per SM, shared up to 228 KiB (H100 whitepaper).
      {"h100", {"H100"}, "GH100 (compute capability 9.0)", 65536, 2048, 255, 256 * kKiB, 8, 4},
      {"h200", {"H200"}, "GH100 (compute capability 9.0)", 65536, 2048, 255, 256 * kKiB, 8, 4},
      // RDNA 2, gfx1030: 2 x 32768 VGPRs, 2 x 16 wave32, granule 16, 16 KiB vector L0 per CU.
      {"rx6900xt",
       {"RX 6900 XT", "RX 6950 XT", "RX 6800 XT", "RX 6800"},
       "Navi 21 (gfx1030, RDNA 2)",
       65536,
       1024,
       256,
       16 * kKiB,
       16,
       2},
      // RDNA 3, gfx1100: 2 x 49152 VGPRs, 2 x 16 wave32, granule 24, 32 KiB vector L0 per CU.
      {"rx7900xtx",
       {"RX 7900 XTX", "RX 7900 XT", "RX 7900 GRE"},
       "Navi 31 (gfx1100, RDNA 3)",
       98304,
       1024,
       256,
       32 * kKiB,
       24,
       2},
  };
  return table;
}

std::optional<GpuBudget> find_budget(const std::string& model_gpu, const std::string& renderer) {
  for (const auto& g : gpu_budgets()) {
    if (model_gpu == g.key) return g;
    if (model_gpu == "auto")
      for (const auto& m : g.matches)
        if (contains_word(renderer, m)) return g;
  }
  return std::nullopt;
}

OccupancyPrediction predict_occupancy(const GpuBudget& gpu, int size, bool indexed_dynamically) {
  OccupancyPrediction p;
  const int needed = kOccupancyBaseRegisters + 4 * size;
  int threads = gpu.max_threads_per_sm;
  if (!indexed_dynamically && needed <= gpu.max_registers_per_thread) {
    const int regs = (needed + gpu.register_granule - 1) / gpu.register_granule * gpu.register_granule;
    const int warps = gpu.registers_per_sm / gpu.register_partitions / (regs * kWarp) * gpu.register_partitions;
    threads = std::min(threads, warps * kWarp);
    p.registers_per_thread = regs;
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
