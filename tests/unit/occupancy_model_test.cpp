// The occupancy model: which GPU model_gpu=auto picks from GL_RENDERER, and its predictions by the formula
// of models/occupancy_model.hpp (registers = roundup(8 + 4 SIZE, granule); warps = floor(file / partitions /
// (32 registers)) * partitions; threads = min(cap, 32 warps); local memory: L1 / (16 SIZE), whole warps).
#include "models/occupancy_model.hpp"

#include <gtest/gtest.h>

#include <set>

#include "experiments/experiments.hpp"
#include "experiments/occupancy.hpp"

namespace oitbench {

namespace {
std::string picked(const std::string& renderer) {
  auto b = find_budget("auto", renderer);
  return b ? b->key : "unknown";
}
GpuBudget budget(const std::string& key) {
  auto b = find_budget(key, "llvmpipe (LLVM 15.0.6, 256 bits)");
  if (!b) throw std::runtime_error("no budget " + key);
  return *b;
}
}  // namespace

TEST(OccupancyModel, AutoMatchesTheRendererStringsOfTheListedGpus) {
  EXPECT_EQ(picked("NVIDIA H200/PCIe/SSE2"), "h200");
  EXPECT_EQ(picked("NVIDIA H200 NVL/PCIe/SSE2"), "h200");
  EXPECT_EQ(picked("NVIDIA H100 80GB HBM3/PCIe/SSE2"), "h100");
  EXPECT_EQ(picked("NVIDIA H100 PCIe/PCIe/SSE2"), "h100");
  EXPECT_EQ(picked("NVIDIA A100-SXM4-80GB/PCIe/SSE2"), "a100");
  EXPECT_EQ(picked("NVIDIA GeForce RTX 4090/PCIe/SSE2"), "rtx4090");
  EXPECT_EQ(picked("NVIDIA GeForce RTX 3090/PCIe/SSE2"), "rtx3090");
  EXPECT_EQ(picked("NVIDIA GeForce RTX 2080 Ti/PCIe/SSE2"), "rtx2080ti");
  EXPECT_EQ(picked("NVIDIA TITAN RTX/PCIe/SSE2"), "rtx2080ti");
  EXPECT_EQ(picked("NVIDIA GeForce GTX 670/PCIe/SSE2"), "gtx670");
  EXPECT_EQ(picked("NVIDIA GeForce GTX 1080/PCIe/SSE2"), "gtx1080");
  EXPECT_EQ(picked("AMD Radeon RX 7900 XTX (radeonsi, navi31, LLVM 15.0.7, DRM 3.54, 6.5.0-1-amd64)"), "rx7900xtx");
  EXPECT_EQ(picked("AMD Radeon RX 7900 XTX"), "rx7900xtx");
  EXPECT_EQ(picked("AMD Radeon RX 7900 XT (radeonsi, navi31, LLVM 15.0.7, DRM 3.54)"), "rx7900xtx");
  EXPECT_EQ(picked("AMD Radeon RX 6900 XT (navi21, LLVM 15.0.6, DRM 3.49, 6.1.0-9-amd64)"), "rx6900xt");
}

TEST(OccupancyModel, AutoSaysUnknownForEverythingElse) {
  EXPECT_EQ(picked("llvmpipe (LLVM 15.0.6, 256 bits)"), "unknown");
  EXPECT_EQ(picked("zink Vulkan 1.3(llvmpipe (LLVM 15.0.6, 256 bits) (MESA_LLVMPIPE))"), "unknown");
  EXPECT_EQ(picked(""), "unknown");
  // Whole words only: another board whose name contains a listed one is not taken for it.
  EXPECT_EQ(picked("NVIDIA RTX A1000 Laptop GPU/PCIe/SSE2"), "unknown");
  EXPECT_EQ(picked("NVIDIA GeForce RTX 2080/PCIe/SSE2"), "unknown");
  EXPECT_EQ(picked("NVIDIA GeForce RTX 40900/PCIe/SSE2"), "unknown");
  EXPECT_EQ(picked("NVIDIA GH1000"), "unknown");
  // An explicit key ignores the renderer.
  EXPECT_EQ(budget("h100").key, "h100");
  EXPECT_FALSE(find_budget("h300", "NVIDIA H100").has_value());
}

TEST(OccupancyModel, EveryBudgetIsAModelGpuValueWithASourceShapedEntry) {
  Registry registry;
  register_all_experiments(registry);
  const ParamSpec* model = nullptr;
  auto params = registry.params_of(*registry.find("occupancy"));
  for (const auto& p : params)
    if (p.name == "model_gpu") model = &p;
  ASSERT_NE(model, nullptr);
  std::set<std::string> keys;
  for (const auto& g : gpu_budgets()) {
    EXPECT_TRUE(keys.insert(g.key).second) << "duplicate key " << g.key;
    EXPECT_NO_THROW(model->check(g.key, "occupancy")) << g.key;
    EXPECT_FALSE(g.matches.empty()) << g.key;
    EXPECT_FALSE(g.chip.empty()) << g.key;
    EXPECT_GT(g.register_granule, 0);
    EXPECT_GT(g.register_partitions, 0);
    EXPECT_EQ(g.registers_per_sm % g.register_partitions, 0) << g.key;
  }
}

TEST(OccupancyModel, H100RegisterArraysFollowTheFormula) {
  auto h100 = budget("h100");
  // SIZE 16: 8 + 64 = 72 registers (a multiple of 8); 16,384 / (72 x 32) = 7 warps per sub-partition,
  // x 4 = 28 warps = 896 of 2,048 threads.
  auto p = predict_occupancy(h100, 16, false);
  EXPECT_TRUE(p.in_registers);
  EXPECT_EQ(p.registers_per_thread, 72);
  EXPECT_EQ(p.threads_per_sm, 896);
  EXPECT_DOUBLE_EQ(p.occupancy, 0.4375);
  // SIZE 32: 136 registers, 3 warps per sub-partition: 12 warps (a per-SM division would say 15).
  p = predict_occupancy(h100, 32, false);
  EXPECT_EQ(p.registers_per_thread, 136);
  EXPECT_EQ(p.threads_per_sm, 384);
  EXPECT_DOUBLE_EQ(p.occupancy, 0.1875);
  // Small arrays hit the thread cap.
  p = predict_occupancy(h100, 1, false);
  EXPECT_EQ(p.registers_per_thread, 16);
  EXPECT_DOUBLE_EQ(p.occupancy, 1.0);
  // SIZE 61 still fits 255 registers (252 -> 256); 62 (256) does not and goes to local memory:
  // 256 KiB / (16 x 62) = 264 threads -> 8 warps.
  p = predict_occupancy(h100, 61, false);
  EXPECT_TRUE(p.in_registers);
  EXPECT_EQ(p.registers_per_thread, 256);
  EXPECT_EQ(p.threads_per_sm, 256);
  p = predict_occupancy(h100, 62, false);
  EXPECT_FALSE(p.in_registers);
  EXPECT_EQ(p.registers_per_thread, 0);
  EXPECT_EQ(p.threads_per_sm, 256);
  // Dynamic indexing: local memory at once. 262,144 / 256 bytes = 1,024 threads.
  p = predict_occupancy(h100, 16, true);
  EXPECT_FALSE(p.in_registers);
  EXPECT_EQ(p.threads_per_sm, 1024);
  EXPECT_DOUBLE_EQ(p.occupancy, 0.5);
  // The H200 is the same chip.
  EXPECT_EQ(predict_occupancy(budget("h200"), 16, false).threads_per_sm, 896);
}

TEST(OccupancyModel, OtherGpusUseTheirOwnCapsGranulesAndPartitions) {
  // Ada and Ampere GA102 cap at 1,536 threads: the same 28 warps are 58%.
  EXPECT_NEAR(predict_occupancy(budget("rtx4090"), 16, false).occupancy, 896.0 / 1536, 1e-12);
  EXPECT_NEAR(predict_occupancy(budget("rtx3090"), 16, false).occupancy, 896.0 / 1536, 1e-12);
  // Turing caps at 1,024: 87.5%; SIZE 4 (24 registers) fills it.
  EXPECT_DOUBLE_EQ(predict_occupancy(budget("rtx2080ti"), 16, false).occupancy, 0.875);
  EXPECT_DOUBLE_EQ(predict_occupancy(budget("rtx2080ti"), 4, false).occupancy, 1.0);
  // A100: 2,048 threads and 192 KiB of L1: dynamic SIZE 16 is 768 threads.
  EXPECT_EQ(predict_occupancy(budget("a100"), 16, true).threads_per_sm, 768);
  // RDNA 2: 72 VGPRs round up to 80 (granule 16); 32,768 / (80 x 32) = 12 waves per SIMD, x 2 = 24 waves
  // = 768 of 1,024 threads per CU.
  auto p = predict_occupancy(budget("rx6900xt"), 16, false);
  EXPECT_EQ(p.registers_per_thread, 80);
  EXPECT_EQ(p.threads_per_sm, 768);
  EXPECT_DOUBLE_EQ(p.occupancy, 0.75);
  // RDNA 3 (Navi 31): 72 is a multiple of 24; 49,152 / 2,304 = 21 waves per SIMD, capped at 16: full.
  p = predict_occupancy(budget("rx7900xtx"), 16, false);
  EXPECT_EQ(p.registers_per_thread, 72);
  EXPECT_DOUBLE_EQ(p.occupancy, 1.0);
  // SIZE 32: 136 -> 144 on both; 7 waves per SIMD on RDNA 2, 10 on RDNA 3.
  EXPECT_EQ(predict_occupancy(budget("rx6900xt"), 32, false).threads_per_sm, 448);
  EXPECT_EQ(predict_occupancy(budget("rx7900xtx"), 32, false).threads_per_sm, 640);
  // GK104's 63 registers per thread send SIZE 16 to local memory: 48 KiB / 256 bytes = 192 threads.
  p = predict_occupancy(budget("gtx670"), 16, false);
  EXPECT_FALSE(p.in_registers);
  EXPECT_EQ(p.threads_per_sm, 192);
  // Never below one warp.
  EXPECT_EQ(predict_occupancy(budget("rx6900xt"), 1024, true).threads_per_sm, 32);
}

}  // namespace oitbench

namespace oitbench {

TEST(MeasuredOccupancy, CountsTheDistinctWarpSlotsOfTheBusiestSm) {
  // 3 SMs of 64 warp slots (2 words each): SM 0 saw slots 0-27, SM 1 slots 0-13 and 32-45, SM 2 nothing;
  // 5 warps reported ids out of range.
  std::vector<unsigned> slots(1 + 3 * 2, 0u);
  slots[0] = 5;
  slots[1] = (1u << 28) - 1;
  slots[3] = (1u << 14) - 1;
  slots[4] = (1u << 14) - 1;
  auto m = count_warp_slots(slots, 3, 64);
  EXPECT_EQ(m.max_slots, 28);
  EXPECT_EQ(m.sms_with_warps, 2);
  EXPECT_DOUBLE_EQ(m.mean_slots, 28.0);
  EXPECT_DOUBLE_EQ(m.occupancy, 0.4375);
  EXPECT_EQ(m.note(),
            "warp slots seen in one untimed pass: at most 28 of 64 on an SM (mean 28.0 over 2 SMs); 5 warp(s) gave "
            "an SM or warp id out of range");
  // Every slot of a 48-warp SM (Ada): full.
  std::vector<unsigned> full = {0u, ~0u, (1u << 16) - 1};
  EXPECT_DOUBLE_EQ(count_warp_slots(full, 1, 48).occupancy, 1.0);
  // Nothing marked, or a buffer that does not match the counts: nothing measured.
  EXPECT_EQ(count_warp_slots(std::vector<unsigned>(7, 0u), 3, 64).sms_with_warps, 0);
  EXPECT_EQ(count_warp_slots(std::vector<unsigned>(7, 0u), 3, 64).note(),
            "no warp marked a slot (the measuring draw produced no fragments?)");
  EXPECT_EQ(count_warp_slots(slots, 4, 64).sms_with_warps, 0);
  EXPECT_EQ(count_warp_slots(slots, 3, 0).sms_with_warps, 0);
}

TEST(MeasuredOccupancy, TheVariantIsBuiltOnlyWhereTheExtensionIs) {
  GlInfo llvmpipe;
  llvmpipe.renderer = "llvmpipe (LLVM 15.0.6, 256 bits)";
  EXPECT_EQ(occupancy_measure_unavailable(llvmpipe),
            "not measured: the driver does not offer GL_NV_shader_thread_group");
  GlInfo nvidia;
  nvidia.renderer = "NVIDIA H200/PCIe/SSE2";
  nvidia.extensions.insert("GL_NV_shader_thread_group");
  EXPECT_EQ(occupancy_measure_unavailable(nvidia), "");
}

}  // namespace oitbench
