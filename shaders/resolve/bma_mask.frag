// BMA: marks the pixels of one depth-complexity interval [lo, hi] in the stencil buffer (the
// draw's stencil reference), so that interval's resolve program runs only on its pixels.
#include "../common/oitbench.glsl"
#define STORAGE_COUNTS
#include "../capture/fragment_storage.glsl"
uniform uint lo, hi;
void main() {
  uint n = imageLoad(fragCounts, ivec2(gl_FragCoord.xy)).r;
  if (n < lo || n > hi) discard;
}
