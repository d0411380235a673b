// STOCHASTIC pass 2 (per MSAA pass): every fragment adds (premultiplied colour, alpha) to the
// samples where it is not behind the stochastic depth (less-or-equal, no writes): the fraction of
// such samples estimates the transmittance in front of it.
#include "../common/oitbench.glsl"
#include "../approx/nodes.glsl"
// The scene effects: the opaque depth tested here (opaque_hides), the shading (self-shadowing).
#include "../scene/backdrop.glsl"
#include "../scene/shade.glsl"
in vec4 vColour;
in vec3 vWorld;
in vec2 vUv;
in float vSoft;
layout(location = 0) out vec4 accumulation;
void main() {
  if (opaque_hides(ivec2(gl_FragCoord.xy), gl_FragCoord.z)) discard;
  vec4 c = approx_fragment_colour(shade_fragment(vColour, vWorld), vUv, vSoft);
  accumulation = vec4(c.rgb * c.a, c.a);
  gl_FragDepth = gl_FragCoord.z;
}
