// The shadow-map pass: each slice's primitives, drawn from the light into that slice's layer of the
// map with additive blending, sum their fragments' optical depth per texel (Kim & Neumann 2001's
// opacity maps, as optical depth so that the prefix over layers is a sum).
#include "../common/oitbench.glsl"
#include "opacity.glsl"
in vec4 vColour;
in vec2 vUv;
in float vSoft;
layout(location = 0) out float opticalDepth;
void main() { opticalDepth = optical_depth(shadow_alpha(vColour, vUv, vSoft)); }
