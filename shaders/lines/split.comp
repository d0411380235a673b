// Stream-split radix sort, one bit per round (count, prefix sum, scatter), stable:
//   PHASE_LOCAL: per block of 256, the exclusive prefix count of keys whose bit is 0, and the block's total
//   PHASE_BLOCKS: exclusive prefix sum over the block totals (one invocation: a few thousand blocks)
//   PHASE_SCATTER: zeros go to their prefix position, ones after all zeros, order kept within each
#include "../common/oitbench.glsl"
#include "bindings.h"
layout(std430, binding = SPLIT_KEYS_IN_BINDING) buffer KeysIn { uint keysIn[]; };
layout(std430, binding = SPLIT_INDICES_IN_BINDING) buffer IndicesIn { uint indicesIn[]; };
layout(std430, binding = SPLIT_KEYS_OUT_BINDING) buffer KeysOut { uint keysOut[]; };
layout(std430, binding = SPLIT_INDICES_OUT_BINDING) buffer IndicesOut { uint indicesOut[]; };
layout(std430, binding = SPLIT_LOCAL_BINDING) buffer Local { uint localPrefix[]; };
layout(std430, binding = SPLIT_BLOCKS_BINDING) buffer Blocks { uint blockSum[]; };  // [0] total zeros, [1 + b] block b
uniform uint count;
uniform uint bit;

bool is_zero(uint i) { return ((keysIn[i] >> bit) & 1u) == 0u; }

#if defined(PHASE_LOCAL)
layout(local_size_x = 256) in;
shared uint scan[256];
void main() {
  uint i = gl_GlobalInvocationID.x, t = gl_LocalInvocationID.x;
  uint flag = (i < count && is_zero(i)) ? 1u : 0u;
  scan[t] = flag;
  barrier();
  for (uint offset = 1u; offset < 256u; offset <<= 1) {  // Hillis-Steele inclusive scan
    uint add = t >= offset ? scan[t - offset] : 0u;
    barrier();
    scan[t] += add;
    barrier();
  }
  if (i < count) localPrefix[i] = scan[t] - flag;
  if (t == 255u) blockSum[1u + gl_WorkGroupID.x] = scan[255];
}
#elif defined(PHASE_BLOCKS)
layout(local_size_x = 1) in;
void main() {
  uint blocks = (count + 255u) / 256u, running = 0u;
  for (uint b = 0u; b < blocks; ++b) {
    uint s = blockSum[1u + b];
    blockSum[1u + b] = running;
    running += s;
  }
  blockSum[0] = running;
}
#elif defined(PHASE_SCATTER)
layout(local_size_x = 256) in;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= count) return;
  uint zerosBefore = blockSum[1u + i / 256u] + localPrefix[i];
  uint dst = is_zero(i) ? zerosBefore : blockSum[0] + (i - zerosBefore);
#ifdef OITBENCH_FAULT_WRONG_RESULT
  if (i == 0u && bit == 0u) dst = count - 1u - dst;  // one element lands in the wrong place
#endif
  keysOut[dst] = keysIn[i];
  indicesOut[dst] = indicesIn[i];
}
#endif
