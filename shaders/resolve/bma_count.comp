// BMA: how many pixels fall in each depth-complexity interval (1-8, 9-16, 17-32, ...), so the
// host skips the intervals with no pixels. One invocation per pixel; histogram[i] for interval i.
#include "../common/oitbench.glsl"
#define STORAGE_COUNTS
#include "../capture/fragment_storage.glsl"
#include "bindings.h"
layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = BMA_HISTOGRAM_BINDING) buffer Histogram { uint histogram[32]; };
void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(fragCounts)))) return;
  uint n = imageLoad(fragCounts, p).r;
  if (n == 0u) return;
  int interval = n <= 8u ? 0 : findMSB(n - 1u) - 2;
  atomicAdd(histogram[min(interval, 31)], 1u);
}
