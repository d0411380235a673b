// Prefix sum, one level of micro/oit/capture/prefix_sum.cpp's scan: groups of 256 invocations,
// each scanning SCAN_BLOCK = 1024 elements (4 per invocation, then a Hillis-Steele scan of the
// invocations' sums in shared memory).
//   SCAN_BLOCKS        scanOut[i] = the sum of the elements before i within its block, and
//                      blockSums[group] = the block's total. The elements come from scanIn, or
//                      (SCAN_FROM_COUNTS) from the per-pixel counts image in row-major order.
//                      SCAN_INCLUSIVE: the sum up to and including i instead (the counts' scan,
//                      each pixel's end, which PPPA's fill counts down from; packed_arrays.glsl).
//   SCAN_ADD           scanOut[i] += blockSums[i / SCAN_BLOCK]: the scanned totals of the blocks
//                      before, so scanOut becomes the scan of the whole array.
// scanIn and scanOut may be the same buffer: an invocation reads its four elements before the
// barrier and writes only those four after it.
#include "../common/oitbench.glsl"
#include "bindings.h"
layout(local_size_x = 256) in;
layout(std430, binding = SCAN_IN_BINDING) buffer ScanIn { uint scanIn[]; };
layout(std430, binding = SCAN_OUT_BINDING) buffer ScanOut { uint scanOut[]; };
layout(std430, binding = SCAN_BLOCK_SUMS_BINDING) buffer BlockSums { uint blockSums[]; };
uniform uint count;
const uint SCAN_BLOCK = 1024u;

#if defined(SCAN_BLOCKS)
#ifdef SCAN_FROM_COUNTS
layout(binding = SCAN_COUNTS_UNIT, r32ui) uniform readonly uimage2D fragCounts;
uint element(uint i) {
  int w = imageSize(fragCounts).x;
  return i < count ? imageLoad(fragCounts, ivec2(int(i) % w, int(i) / w)).r : 0u;
}
#else
uint element(uint i) { return i < count ? scanIn[i] : 0u; }
#endif

shared uint partial[256];
void main() {
  uint t = gl_LocalInvocationID.x, base = gl_WorkGroupID.x * SCAN_BLOCK + t * 4u;
  uint v0 = element(base), v1 = element(base + 1u), v2 = element(base + 2u), v3 = element(base + 3u);
  uint sum = v0 + v1 + v2 + v3;
  partial[t] = sum;
  barrier();
  for (uint offset = 1u; offset < 256u; offset <<= 1) {
    uint add = t >= offset ? partial[t - offset] : 0u;
    barrier();
    partial[t] += add;
    barrier();
  }
  uint before = partial[t] - sum;
#ifdef SCAN_INCLUSIVE
  uvec4 scanned = before + uvec4(v0, v0 + v1, v0 + v1 + v2, sum);
#else
  uvec4 scanned = before + uvec4(0u, v0, v0 + v1, v0 + v1 + v2);
#endif
  for (uint k = 0u; k < 4u; ++k)
    if (base + k < count) scanOut[base + k] = scanned[k];
  if (t == 255u) blockSums[gl_WorkGroupID.x] = partial[255];
}
#elif defined(SCAN_ADD)
void main() {
  uint base = gl_WorkGroupID.x * SCAN_BLOCK + gl_LocalInvocationID.x * 4u, add = blockSums[gl_WorkGroupID.x];
  for (uint k = 0u; k < 4u; ++k)
    if (base + k < count) scanOut[base + k] += add;
}
#else
#error "define SCAN_BLOCKS or SCAN_ADD"
#endif
