// Weighted blended OIT (McGuire & Bavoil 2013), one geometry pass into two targets:
//   accumulation (additive):    (c * a * w(z, a), a * w(z, a))
//   revealage (zero, 1 - src):  prod (1 - a)
// WEIGHT_NONE: w = 1 (Bavoil & Myers's weighted average); WEIGHT_EQ7: McGuire & Bavoil Eq. 7 on
// the view-space distance; WEIGHT_EQ10: Eq. 10 on the window depth gl_FragCoord.z.
#include "../common/oitbench.glsl"
#include "nodes.glsl"
#include "../scene/fragment.glsl"
uniform vec2 nearFar;  // the projection's planes (for the view-space distance)
layout(location = 0) out vec4 accumulation;
layout(location = 1) out vec4 revealage;

float weight(float d, float a) {
#if defined(WEIGHT_NONE)
  return 1.0;
#elif defined(WEIGHT_EQ7)
  float z = nearFar.x * nearFar.y / (nearFar.y - d * (nearFar.y - nearFar.x));
  return clamp(10.0 / (1e-5 + pow(z / 5.0, 2.0) + pow(z / 200.0, 6.0)), 1e-2, 3e3);
#elif defined(WEIGHT_EQ10)
  return clamp(3e3 * pow(1.0 - d, 3.0), 1e-2, 3e3);
#else
#error "define WEIGHT_NONE, WEIGHT_EQ7 or WEIGHT_EQ10"
#endif
}

void main() {
  SceneFragment f = scene_fragment();
  vec4 c = scene_fragment_rgba8(f);
  float w = c.a * weight(f.depth, c.a);
  accumulation = vec4(c.rgb * w, w);
  revealage = vec4(c.a);
}
