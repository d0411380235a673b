// Local array size vs time: Knowles et al. 2013 (BMA), figure 3. Every fragment declares
// `vec4 myArray[SIZE]` and uses all of it, so no compiler can drop it.
//   VARIANT_DYNAMIC:  filled and read through indices that depend on a uniform: the array must live
//                     in local (scratch) memory.
//   VARIANT_UNROLLED: filled and summed by constant-trip loops: once unrolled every index is a
//                     constant and the compiler may keep the array in registers.
// Every value is a small integer, so the result is exact and the CPU reference compares bit for bit.
//   OCCUPANCY_MEASURE (injected only where the driver offers GL_NV_shader_thread_group, for one untimed draw
//                     at validation): one lane of each warp marks the warp slot it occupies on its SM in
//                     occupancy_slots; the slots seen per SM over the draw, over gl_WarpsPerSMNV, are the
//                     measured occupancy (docs/experiments/occupancy.md).
#if defined(OCCUPANCY_MEASURE)
#extension GL_NV_shader_thread_group : require
#endif
#include "../common/oitbench.glsl"
#include "bindings.h"

uniform int zero;  // always 0; unknown to the compiler
layout(location = 0) out vec4 fragColour;

#if defined(OCCUPANCY_MEASURE)
// [0]: warps whose SM or warp id was out of range; then per SM, ceil(gl_WarpsPerSMNV / 32) words, one bit
// per warp slot.
layout(std430, binding = OCCUPANCY_SLOTS_BINDING) buffer OccupancySlots { uint occupancy_slots[]; };

void mark_warp_slot() {
  // The lowest lane that is not a helper invocation (helpers' atomics are discarded) speaks for its warp.
  uint lanes = ballotThreadNV(!gl_HelperInvocation);
  if (lanes == 0u || gl_ThreadInWarpNV != uint(findLSB(lanes))) return;
  if (gl_SMIDNV < gl_SMCountNV && gl_WarpIDNV < gl_WarpsPerSMNV) {
    uint words = (gl_WarpsPerSMNV + 31u) / 32u;
    atomicOr(occupancy_slots[1u + gl_SMIDNV * words + gl_WarpIDNV / 32u], 1u << (gl_WarpIDNV % 32u));
  } else {
    atomicAdd(occupancy_slots[0], 1u);
  }
}
#endif

vec4 element(ivec2 p, int i) {
  return vec4(float((p.x * (i + 1) + p.y) & 1023), float((p.y * (i + 3) + zero) & 511), float(i),
              float((p.x ^ i) & 63));
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 myArray[SIZE];
#if defined(VARIANT_DYNAMIC)
  for (int i = 0; i < SIZE; ++i) myArray[(i + zero) % SIZE] = element(p, i);
  vec4 r = myArray[(p.x + zero) % SIZE] + myArray[(p.y + zero) % SIZE];
#elif defined(VARIANT_UNROLLED)
  for (int i = 0; i < SIZE; ++i) myArray[i] = element(p, i);
  vec4 r = vec4(0.0);
  for (int i = 0; i < SIZE; ++i) r += myArray[i] * float(i % 3 + 1);
#else
#error "define VARIANT_DYNAMIC or VARIANT_UNROLLED"
#endif
#ifdef OITBENCH_FAULT_WRONG_RESULT
  if (p == ivec2(1, 1)) r.x += 1.0;  // one pixel off by one: the validator must notice
#endif
#if defined(OCCUPANCY_MEASURE)
  mark_warp_slot();  // after the array's work, in uniform control flow: every lane of the warp takes part
#endif
  fragColour = r + oitbench_fault_hang(zero);
}
