// The exact-OIT resolve as a fragment shader, written once against the storage API (the sorts:
// resolve_pixel.glsl, from the library in shaders/sorts/). Drawn as a full-screen triangle with
// additive blending onto a cleared target: rgb is the composited colour, alpha counts how often
// the pixel was resolved (BMA must resolve each covered pixel exactly once).
#if defined(SORT_PACKED_KEY64)
#extension GL_ARB_gpu_shader_int64 : require
#endif
#include "../common/oitbench.glsl"
#include "../capture/fragment_storage.glsl"

// Early tests: BMA's stencil mask must stop an interval's program before it runs on the other
// intervals' pixels; without this a driver may test the stencil after the shader (it reads
// images and may discard), and every interval pass would cost a full-screen resolve.
layout(early_fragment_tests) in;

#include "../scene/backdrop.glsl"
vec3 backdrop;  // behind this pixel's layers: resolve_pixel() blends onto it
uniform int zero;  // always 0 (fault hooks)
layout(location = 0) out vec4 fragColour;

#include "resolve_pixel.glsl"

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  uint head = FRAG_BEGIN(p);
  if (!FRAG_VALID(head)) discard;
  backdrop = backdrop_colour(p);
  vec3 c = resolve_pixel(head);
#ifdef OITBENCH_FAULT_WRONG_RESULT
  if (p.x == p.y) c.r += 1.0 / 64.0;  // the diagonal off by 4/255: the validator must notice
#endif
  fragColour = vec4(c + oitbench_fault_hang(zero), 1.0);
}
