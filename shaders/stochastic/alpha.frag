// STOCHASTIC pass 3: the exact total transmittance, prod (1 - alpha), by multiplicative blending
// (zero, one minus source colour) into R32F cleared to 1.
#include "../common/oitbench.glsl"
#include "../approx/nodes.glsl"
// The scene effects: the opaque depth tested here (opaque_hides), the shading (self-shadowing).
#include "../scene/backdrop.glsl"
#include "../scene/shade.glsl"
in vec4 vColour;
in vec3 vWorld;
in vec2 vUv;
in float vSoft;
layout(location = 0) out vec4 alpha;
void main() {
  if (opaque_hides(ivec2(gl_FragCoord.xy), gl_FragCoord.z)) discard; alpha = vec4(approx_fragment_colour(shade_fragment(vColour, vWorld), vUv, vSoft).a); }
