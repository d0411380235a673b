// STOCHASTIC pass 2 (per MSAA pass): every fragment adds (premultiplied colour, alpha) to the
// samples where it is not behind the stochastic depth (less-or-equal, no writes): the fraction of
// such samples estimates the transmittance in front of it.
#include "../common/oitbench.glsl"
#include "../approx/nodes.glsl"
// The scene effects: the opaque depth tested here (opaque_hides), the shading (self-shadowing).
#include "../scene/backdrop.glsl"
#include "../scene/fragment.glsl"
layout(location = 0) out vec4 accumulation;
void main() {
  SceneFragment f = scene_fragment();
  if (opaque_hides(ivec2(gl_FragCoord.xy), f.depth)) discard;
  vec4 c = scene_fragment_rgba8(f);
  accumulation = vec4(c.rgb * c.a, c.a);
  gl_FragDepth = f.depth;
}
