// The viewer's depth complexity: each pixel's captured fragments, counted by walking its storage
// through the FRAG_* API only (so any storage layout works), plus the peak and the total.
#include "../common/oitbench.glsl"
#include "bindings.h"
#include "../capture/fragment_storage.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = DEPTH_COUNTS_UNIT, r32ui) uniform writeonly uimage2D depthCounts;
layout(std430, binding = DEPTH_STATS_BINDING) buffer DepthStats {
  uint peak;
  uint total;
};
// A damaged list (a cycle) must not hang the viewer; no pixel of a real scene is this deep.
const uint kMaxWalk = 65535u;
void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(depthCounts)))) return;
  uint n = 0u;
  for (uint node = FRAG_BEGIN(p); FRAG_VALID(node) && n < kMaxWalk; node = FRAG_NEXT(node)) ++n;
  imageStore(depthCounts, p, uvec4(n));
  if (n > 0u) {
    atomicMax(peak, n);
    atomicAdd(total, n);
  }
}
