// WBOIT composite: the weighted average colour covers 1 - revealage of the background. The
// average divides by the accumulated weight, which is 0 where every fragment has alpha 0: the
// guard clamps it (APPROX_UNGUARDED removes the clamp, which turns such pixels into NaN).
#include "../common/oitbench.glsl"
#include "bindings.h"
layout(binding = APPROX_ACCUM_UNIT) uniform sampler2D accumulation;
layout(binding = APPROX_REVEAL_UNIT) uniform sampler2D revealage;
#include "../scene/backdrop.glsl"
uniform int zero;
layout(location = 0) out vec4 fragColour;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 acc = texelFetch(accumulation, p, 0);
  float r = texelFetch(revealage, p, 0).r;
#if defined(APPROX_UNGUARDED)
  vec3 average = acc.rgb / acc.a;
#else
  vec3 average = acc.rgb / clamp(acc.a, 1e-4, 5e4);
#endif
  vec3 c = average * (1.0 - r) + backdrop_colour(p) * r;
#ifdef OITBENCH_FAULT_WRONG_RESULT
  if (p.x == p.y) c.r += 1.0 / 16.0;
#endif
  fragColour = vec4(c + oitbench_fault_hang(zero), 1.0);
}
