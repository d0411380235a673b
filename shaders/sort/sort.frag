// Sorting in a full-screen fragment pass: one invocation per pixel (Brüll 2018, 4.5).
#if defined(SORT_PACKED_KEY64)
#extension GL_ARB_gpu_shader_int64 : require
#endif
#include "sort_pixel.glsl"

layout(location = 0) out uint first_payload;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  process_pixel(p);
  first_payload = SORT_AT(0).y + uint(oitbench_fault_hang(zero));
}
