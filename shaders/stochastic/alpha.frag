// STOCHASTIC pass 3: the exact total transmittance, prod (1 - alpha), by multiplicative blending
// (zero, one minus source colour) into R32F cleared to 1.
#include "../common/oitbench.glsl"
#include "../approx/nodes.glsl"
in vec4 vColour;
in vec2 vUv;
in float vSoft;
layout(location = 0) out vec4 alpha;
void main() { alpha = vec4(approx_fragment_colour(vColour, vUv, vSoft).a); }
