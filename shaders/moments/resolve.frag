// MBOIT resolve: the transmittance-weighted average colour covers 1 - exp(-b0) of the backdrop.
#include "../common/oitbench.glsl"
#include "bindings.h"
layout(binding = MOMENTS_B0_UNIT) uniform sampler2D b0Moment;
layout(binding = MOMENTS_ACCUM_UNIT) uniform sampler2D weightedColour;
#include "../scene/backdrop.glsl"
uniform int zero;
layout(location = 0) out vec4 fragColour;


void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  float b0 = texelFetch(b0Moment, p, 0).r;
  vec4 acc = texelFetch(weightedColour, p, 0);
  float total = exp(-b0);
  vec3 behind = backdrop_colour(p);
  vec3 c = acc.a > 0.0 ? acc.rgb / acc.a * (1.0 - total) + behind * total : behind;
#ifdef OITBENCH_FAULT_WRONG_RESULT
  if ((p.x + p.y) % 8 == 0) c.r += 1.0 / 16.0;  // 12.5% of the pixels: beyond 16-bit's allowance
#endif
  fragColour = vec4(c + oitbench_fault_hang(zero), 1.0);
}
