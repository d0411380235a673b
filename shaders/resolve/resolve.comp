// The exact-OIT resolve as a compute pass (the paper's CUDA rows, in GLSL compute): one invocation
// per pixel runs the same resolve_pixel() as resolve.frag and stores the composited colour into
// the target image, alpha 1 for a resolved pixel (uncovered pixels keep the cleared 0 alpha).
// Groups cover CS_GROUP_X x CS_GROUP_Y pixels (default 8x8). The sorts load, then sort.
//
// How invocations lie on the group's pixels (group_pixel()): the group is one-dimensional, and
// where both sides are multiples of 4 its invocations run through 4x4-pixel blocks, 16 at a time,
// each block's top 4x2 half first: the pixels a fragment shader's 8-wide vector holds on llvmpipe,
// whose rasterizer (the capture's too) visits pixels in those blocks, so the lists' nodes a vector
// walks in step were stored side by side. llvmpipe runs a group's invocations as vectors of 8
// consecutive ones; with 8-wide rows (8x1) a vector's 8 next-pointer loads per step fall in two
// blocks' nodes, and its 4x4 groups filled only half of each vector (4-wide rows): measured on
// planes fwd, the compute resolve was 0.44-0.52x of BASE-IS in rows, 0.67-0.71x in blocks on a
// loaded host, 0.75x and 0.97x with one llvmpipe thread (docs/drivers.md, "The compute resolve's
// loads"). Other shapes (8x1, 16x1, ...) run in rows. Which invocation resolves a pixel changes no
// result: each pixel's resolve is the same code on the same list.
#if defined(SORT_PACKED_KEY64)
#extension GL_ARB_gpu_shader_int64 : require
#endif
#include "../common/oitbench.glsl"
#include "../capture/fragment_storage.glsl"
#include "bindings.h"

layout(local_size_x = CS_GROUP_X * CS_GROUP_Y) in;

// The pixel of the group's invocation i, from the group's corner.
ivec2 group_pixel(uint i) {
#if CS_GROUP_X % 4 == 0 && CS_GROUP_Y % 4 == 0
  uint block = i >> 4u, blocksPerRow = uint(CS_GROUP_X / 4);
  return ivec2((block % blocksPerRow) * 4u + (i & 3u), (block / blocksPerRow) * 4u + ((i >> 2u) & 3u));
#else
  return ivec2(i % uint(CS_GROUP_X), i / uint(CS_GROUP_X));
#endif
}
layout(binding = OIT_RESOLVED_IMAGE_UNIT, rgba32f) uniform writeonly image2D resolved;
#include "../scene/backdrop.glsl"
vec3 backdrop;  // behind this pixel's layers: resolve_pixel() blends onto it
uniform int zero;  // always 0 (fault hooks)

#include "resolve_pixel.glsl"

// No early return: a return before the resolve puts the whole resolve under an execution mask in
// llvmpipe's vectorised compute code (every local-array store then masked); a lane outside the
// screen resolves the nearest pixel inside it instead, and only valid pixels store. Measured on
// planes fwd 256x256 (CS-IS, quiet, 3 alternating runs of 11 repetitions): resolve 126-134 ms with
// the returns, 114-121 ms without (docs/drivers.md, "The compute resolve's loads").
void main() {
  ivec2 p = ivec2(gl_WorkGroupID.xy) * ivec2(CS_GROUP_X, CS_GROUP_Y) + group_pixel(gl_LocalInvocationIndex);
  bool inside = all(lessThan(p, FRAG_SCREEN_SIZE()));
  ivec2 q = min(p, FRAG_SCREEN_SIZE() - 1);
  uint head = FRAG_BEGIN(q);
  bool valid = inside && FRAG_VALID(head);  // before resolve_pixel: a storage's FRAG_VALID may read its state
  backdrop = backdrop_colour(q);
  vec3 c = resolve_pixel(head);  // no fragments: the backdrop, not stored
#ifdef OITBENCH_FAULT_WRONG_RESULT
  if (p.x == p.y) c.r += 1.0 / 64.0;  // the diagonal off by 4/255: the validator must notice
#endif
  if (valid) imageStore(resolved, p, vec4(c + oitbench_fault_hang(zero), 1.0));
}
