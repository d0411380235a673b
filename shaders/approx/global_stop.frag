// GLOBAL-SORT with 3DGS's early termination (early_stop > 0; Kerbl et al. 2023): the splats arrive
// sorted near to far (keys.comp's SPLAT_KEYS_NEAR_FIRST) and are composited front to back ("under"). Each
// pixel's transmittance T lives in an r32f image: a fragment reads it, and is not blended when it would
// take T below EARLY_STOP; the pixel then stops (T is stored negated: every later fragment is dropped,
// and the resolve, approx/global_stop_resolve.frag, shows the backdrop through |T|). The colour
// T alpha c adds up in the accumulation target.
// The read-modify-write of T needs the pixel's fragments in submission order: GLOBAL_STOP_INTERLOCK
// (ARB_fragment_shader_interlock, ordered) on drivers that have it; llvmpipe and lavapipe shade a
// pixel's fragments in submission order (one thread per tile, primitives in order), as the approximate
// techniques' models assume too, and the case's CPU model checks it.
#if defined(GLOBAL_STOP_INTERLOCK)
#extension GL_ARB_fragment_shader_interlock : require
#endif
#include "../common/oitbench.glsl"
#include "nodes.glsl"
#include "../scene/fragment.glsl"
#include "bindings.h"
layout(early_fragment_tests) in;
#if defined(GLOBAL_STOP_INTERLOCK)
layout(pixel_interlock_ordered) in;
#endif
layout(r32f, binding = APPROX_TRANSMITTANCE_IMAGE_UNIT) coherent uniform image2D transmittance;
uniform int zero;
layout(location = 0) out vec4 fragColour;
void main() {
  SceneFragment f = scene_fragment();
  vec4 c = scene_fragment_rgba8(f);
#ifdef OITBENCH_FAULT_WRONG_RESULT
  if (ivec2(gl_FragCoord.xy).x == ivec2(gl_FragCoord.xy).y) c.r = min(c.r + 0.25, 1.0);
#endif
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec3 add = vec3(0.0);
#if defined(GLOBAL_STOP_INTERLOCK)
  beginInvocationInterlockARB();
#endif
  if (!gl_HelperInvocation) {
    float t = imageLoad(transmittance, p).r;
    float next = t * (1.0 - c.a);
    if (t > 0.0 && next < EARLY_STOP) {
      imageStore(transmittance, p, vec4(-t));  // stopped here: nothing more is blended
    } else if (t > 0.0) {
      add = t * c.a * c.rgb;
      imageStore(transmittance, p, vec4(next));
    }
  }
#if defined(GLOBAL_STOP_INTERLOCK)
  endInvocationInterlockARB();
#endif
  fragColour = vec4(add + oitbench_fault_hang(zero), 0.0);
}
