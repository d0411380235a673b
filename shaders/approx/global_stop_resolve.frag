// GLOBAL-SORT with early termination, its resolve: the colour approx/global_stop.frag accumulated front
// to back, plus the backdrop seen through the transmittance left (|T|: negative where the pixel stopped).
#include "../common/oitbench.glsl"
#include "bindings.h"
layout(binding = APPROX_ACCUM_UNIT) uniform sampler2D accumulation;
layout(binding = APPROX_REVEAL_UNIT) uniform sampler2D transmittance;
#include "../scene/backdrop.glsl"
uniform int zero;
layout(location = 0) out vec4 fragColour;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec3 c = texelFetch(accumulation, p, 0).rgb + abs(texelFetch(transmittance, p, 0).r) * backdrop_colour(p);
  fragColour = vec4(c + oitbench_fault_hang(zero), 1.0);
}
