// WOIT resolve: the transmittance-weighted average colour covers 1 - exp(-c0) of the backdrop, c0
// (the scaling coefficient) being the pixel's total absorbance.
#include "../common/oitbench.glsl"
#include "bindings.h"
layout(binding = WAVELETS_COEFFS_UNIT) uniform sampler2DArray coefficients;
layout(binding = WAVELETS_ACCUM_UNIT) uniform sampler2D weightedColour;
#include "../scene/backdrop.glsl"
uniform int zero;
layout(location = 0) out vec4 fragColour;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  float total = exp(-texelFetch(coefficients, ivec3(p, 0), 0).x);
  vec4 acc = texelFetch(weightedColour, p, 0);
  vec3 behind = backdrop_colour(p);
  vec3 c = acc.a > 0.0 ? acc.rgb / acc.a * (1.0 - total) + behind * total : behind;
#ifdef OITBENCH_FAULT_WRONG_RESULT
  if ((p.x + p.y) % 8 == 0) c.r += 1.0 / 16.0;  // 12.5% of the pixels: beyond the model's allowance
#endif
  fragColour = vec4(c + oitbench_fault_hang(zero), 1.0);
}
