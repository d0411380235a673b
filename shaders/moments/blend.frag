// MBOIT pass 2: every fragment adds its premultiplied colour and alpha weighted by the
// transmittance its pixel's moments reconstruct at its depth (additive, RGBA32F).
#include "../common/oitbench.glsl"
#include "../approx/nodes.glsl"
#include "bindings.h"
#include "moment_math.glsl"
// The scene effects: the opaque depth tested here (opaque_hides), the shading (self-shadowing).
#include "../scene/backdrop.glsl"
#include "../scene/fragment.glsl"
uniform vec2 nearFar;
uniform vec2 depthRange;  // the view depths the warp maps to [-1, 1]
uniform float momentBias;
uniform float overestimation;
layout(binding = MOMENTS_B0_UNIT) uniform sampler2D b0Moment;
layout(binding = MOMENTS_LOW_UNIT) uniform sampler2D lowMoments;
#if MOMENT_COUNT > 4
layout(binding = MOMENTS_HIGH_UNIT) uniform sampler2D highMoments;
#endif
layout(location = 0) out vec4 weighted;
void main() {
  SceneFragment f = scene_fragment();
  if (opaque_hides(ivec2(gl_FragCoord.xy), f.depth)) discard;
  vec4 c = scene_fragment_rgba8(f);
  ivec2 px = ivec2(gl_FragCoord.xy);
  float b0 = texelFetch(b0Moment, px, 0).r;
  float raw[MOMENT_COUNT];
  vec4 low = texelFetch(lowMoments, px, 0);
  raw[0] = low.x;
  raw[1] = low.y;
  raw[2] = low.z;
  raw[3] = low.w;
#if MOMENT_COUNT > 4
  vec4 high = texelFetch(highMoments, px, 0);
  raw[4] = high.x;
  raw[5] = high.y;
#endif
#if MOMENT_COUNT > 6
  raw[6] = high.z;
  raw[7] = high.w;
#endif
  float t = b0 > 0.0 ? moment_transmittance(b0, raw, moment_warp(f.depth, nearFar, depthRange), momentBias, overestimation)
                     : 1.0;
  weighted = vec4(c.rgb * c.a * t, c.a * t);
}
