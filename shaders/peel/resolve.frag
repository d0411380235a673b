// The depth peeling composite: the front layers (blended front to back, transmittance in alpha),
// then DDP's back layers (blended back to front, coverage in alpha), then the backdrop.
#include "../common/oitbench.glsl"
#include "bindings.h"
layout(binding = PEEL_FRONT_ACCUM_UNIT) uniform sampler2D frontAccum;
#if defined(DUAL)
layout(binding = PEEL_BACK_ACCUM_UNIT) uniform sampler2D backAccum;
#endif
#include "../scene/backdrop.glsl"
uniform int zero;
layout(location = 0) out vec4 fragColour;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 front = texelFetch(frontAccum, p, 0);
  vec3 behind = backdrop_colour(p);
#if defined(DUAL)
  vec4 back = texelFetch(backAccum, p, 0);
  behind = back.rgb + (1.0 - back.a) * behind;
#endif
  vec3 c = front.rgb + front.a * behind;
#ifdef OITBENCH_FAULT_WRONG_RESULT
  if (p.x == p.y) c.r += 1.0 / 16.0;  // the diagonal off by 16/255: the validator must notice
#endif
  fragColour = vec4(c + oitbench_fault_hang(zero), 1.0);
}
