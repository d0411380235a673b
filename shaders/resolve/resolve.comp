// The exact-OIT resolve as a compute pass (the paper's CUDA rows, in GLSL compute): one invocation
// per pixel runs the same resolve_pixel() as resolve.frag and stores the composited colour into
// the target image, alpha 1 for a resolved pixel (uncovered pixels keep the cleared 0 alpha).
// Groups are CS_GROUP_X x CS_GROUP_Y pixels; the default is 8-wide rows (8x1): a stream-form
// resolve was miscompiled here with 4x4 groups (PLATFORM.md). The sorts load, then sort.
#if defined(SORT_PACKED_KEY64)
#extension GL_ARB_gpu_shader_int64 : require
#endif
#include "../common/oitbench.glsl"
#include "../capture/fragment_storage.glsl"
#include "bindings.h"

layout(local_size_x = CS_GROUP_X, local_size_y = CS_GROUP_Y) in;
layout(binding = OIT_RESOLVED_IMAGE_UNIT, rgba32f) uniform writeonly image2D resolved;
#include "../scene/backdrop.glsl"
vec3 backdrop;  // behind this pixel's layers: resolve_pixel() blends onto it
uniform int zero;  // always 0 (fault hooks)

#include "resolve_pixel.glsl"

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, FRAG_SCREEN_SIZE()))) return;
  uint head = FRAG_BEGIN(p);
  if (!FRAG_VALID(head)) return;
  backdrop = backdrop_colour(p);
  vec3 c = resolve_pixel(head);
#ifdef OITBENCH_FAULT_WRONG_RESULT
  if (p.x == p.y) c.r += 1.0 / 64.0;  // the diagonal off by 4/255: the validator must notice
#endif
  imageStore(resolved, p, vec4(c + oitbench_fault_hang(zero), 1.0));
}
