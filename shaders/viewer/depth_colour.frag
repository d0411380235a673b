// Depth complexity in false colour: blue (1 fragment) -> green -> red (the peak) on a log scale,
// black where no fragment landed.
#include "../common/oitbench.glsl"
#include "bindings.h"
layout(binding = DEPTH_COUNTS_UNIT, r32ui) uniform readonly uimage2D depthCounts;
layout(std430, binding = DEPTH_STATS_BINDING) readonly buffer DepthStats {
  uint peak;
  uint total;
};
uniform vec2 texelsPerPixel;
out vec4 colour;
void main() {
  ivec2 p = min(ivec2(gl_FragCoord.xy * texelsPerPixel), imageSize(depthCounts) - 1);
  uint n = imageLoad(depthCounts, p).r;
  float t = peak > 1u ? log2(float(n)) / log2(float(peak)) : 1.0;
  vec3 c = t < 0.5 ? mix(vec3(0, 0, 1), vec3(0, 1, 0), t * 2.0) : mix(vec3(0, 1, 0), vec3(1, 0, 0), t * 2.0 - 1.0);
  colour = vec4(n == 0u ? vec3(0.0) : c, 1.0);
}
