// STOCHASTIC pass 3: the exact total transmittance, prod (1 - alpha), by multiplicative blending
// (zero, one minus source colour) into R32F cleared to 1.
#include "../common/oitbench.glsl"
#include "../approx/nodes.glsl"
// The scene effects: the opaque depth tested here (opaque_hides), the shading (self-shadowing).
#include "../scene/backdrop.glsl"
#include "../scene/fragment.glsl"
layout(location = 0) out vec4 alpha;
void main() {
  SceneFragment f = scene_fragment();
  if (opaque_hides(ivec2(gl_FragCoord.xy), f.depth)) discard;
  alpha = vec4(scene_fragment_rgba8(f).a);
}
