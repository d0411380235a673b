// Pass 2 of the AT family: every fragment adds its contribution alpha * c * vis(z) (Eq. 2.4) to
// an additive RGBA32F accumulation (in submission order per pixel on a serial rasteriser); alpha
// accumulates alpha * vis(z), the opacity the resolve checks the colour against.
#include "../common/oitbench.glsl"
#include "../storage/storage.glsl"
#include "visibility.glsl"
#include "../scene/shade.glsl"
in vec4 vColour;
in vec2 vUv;
in float vSoft;
in vec3 vWorld;
layout(location = 0) out vec4 fragColour;
void main() {
  vec4 c = approx_fragment_colour(shade_fragment(vColour, vWorld), vUv, vSoft);
  float w = c.a * visibility(ivec2(gl_FragCoord.xy), gl_FragCoord.z);
  fragColour = vec4(c.rgb * w, w);
}
