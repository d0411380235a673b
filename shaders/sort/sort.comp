// Sorting in a compute pass: one invocation per pixel, 8x8 pixel tiles.
#if defined(SORT_PACKED_KEY64)
#extension GL_ARB_gpu_shader_int64 : require
#endif
#include "sort_pixel.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, image_size))) return;
  process_pixel(p);
  if (oitbench_fault_hang(zero) != 0.0) out_frags[0] = uvec2(0u);
}
