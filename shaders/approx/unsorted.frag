// No OIT: plain "over" blending (src alpha, 1 - src alpha) in submission order onto the background.
#include "../common/oitbench.glsl"
#include "nodes.glsl"
#include "../scene/fragment.glsl"
uniform int zero;
layout(location = 0) out vec4 fragColour;
void main() {
  SceneFragment f = scene_fragment();
  vec4 c = scene_fragment_rgba8(f);
#ifdef OITBENCH_FAULT_WRONG_RESULT
  if (ivec2(gl_FragCoord.xy).x == ivec2(gl_FragCoord.xy).y) c.r = min(c.r + 0.25, 1.0);
#endif
  fragColour = vec4(c.rgb + oitbench_fault_hang(zero), c.a);
}
