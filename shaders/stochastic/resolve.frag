// STOCHASTIC resolve with the alpha correction (Enderton et al. 2010, section 3.3): the samples'
// average colour, rescaled so that its opacity is the exact 1 - prod (1 - alpha), over the backdrop.
#include "../common/oitbench.glsl"
#include "bindings.h"
layout(binding = STOCHASTIC_ACCUM_UNIT) uniform sampler2DMS accumulation;
layout(binding = STOCHASTIC_TOTAL_UNIT) uniform sampler2D totalTransmittance;
#include "../scene/backdrop.glsl"
uniform int zero;
layout(location = 0) out vec4 fragColour;


void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 acc = vec4(0.0);
  for (int s = 0; s < MSAA_SAMPLES; ++s) acc += texelFetch(accumulation, p, s);
  acc /= float(MSAA_SAMPLES * STOCHASTIC_PASSES);
  float total = texelFetch(totalTransmittance, p, 0).r;
  vec3 behind = backdrop_colour(p);
  vec3 c = acc.a > 0.0 ? acc.rgb * (1.0 - total) / acc.a + behind * total : behind;
#ifdef OITBENCH_FAULT_WRONG_RESULT
  if (p.x == p.y) c.r += 1.0 / 16.0;
#endif
  fragColour = vec4(c + oitbench_fault_hang(zero), 1.0);
}
