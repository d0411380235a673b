// MBOIT pass 1: every fragment adds its absorbance -ln(1 - alpha) and its moments (additive
// blending into MOMENTS_B0 and one or two moment targets, 32- or 16-bit float).
#include "../common/oitbench.glsl"
#include "../approx/nodes.glsl"
#include "moment_math.glsl"
// The scene effects: the opaque depth tested here (opaque_hides), the shading (self-shadowing).
#include "../scene/backdrop.glsl"
#include "../scene/fragment.glsl"
uniform vec2 nearFar;
uniform vec2 depthRange;  // the view depths the warp maps to [-1, 1]
uniform int zero;
layout(location = 0) out float outB0;
layout(location = 1) out vec4 outLow;
#if MOMENT_COUNT > 4
layout(location = 2) out vec4 outHigh;
#endif
void main() {
  SceneFragment f = scene_fragment();
  if (opaque_hides(ivec2(gl_FragCoord.xy), f.depth)) discard;
  vec4 c = scene_fragment_rgba8(f);
  float a = c.a >= 1.0 ? ABSORBANCE_MAX : min(-log(1.0 - c.a), ABSORBANCE_MAX);
  float b[MOMENT_COUNT];
  moment_contribution(moment_warp(f.depth, nearFar, depthRange), a, b);
  outB0 = a + oitbench_fault_hang(zero);
  outLow = vec4(b[0], b[1], b[2], b[3]);
#if MOMENT_COUNT == 6
  outHigh = vec4(b[4], b[5], 0.0, 0.0);
#elif MOMENT_COUNT == 8
  outHigh = vec4(b[4], b[5], b[6], b[7]);
#endif
}
