// No OIT: plain "over" blending (src alpha, 1 - src alpha) in submission order onto the background.
#include "../common/oitbench.glsl"
#include "nodes.glsl"
#include "../scene/shade.glsl"
in vec4 vColour;
in vec2 vUv;
in float vSoft;
in vec3 vWorld;
uniform int zero;
layout(location = 0) out vec4 fragColour;
void main() {
  vec4 c = approx_fragment_colour(shade_fragment(vColour, vWorld), vUv, vSoft);
#ifdef OITBENCH_FAULT_WRONG_RESULT
  if (ivec2(gl_FragCoord.xy).x == ivec2(gl_FragCoord.xy).y) c.r = min(c.r + 0.25, 1.0);
#endif
  fragColour = vec4(c.rgb + oitbench_fault_hang(zero), c.a);
}
