// The sorted segment order as an element buffer for one GL_LINES draw: segment sorted[j]'s two
// vertex indices (Mesh::line_indices) at elements[2j], elements[2j + 1].
#include "../common/oitbench.glsl"
layout(local_size_x = 256) in;
layout(std430, binding = 0) readonly buffer Sorted { uint sorted[]; };
layout(std430, binding = 1) writeonly buffer Elements { uint elements[]; };
layout(std430, binding = 2) readonly buffer Lines { uint lines[]; };
uniform uint segments;
void main() {
  uint j = gl_GlobalInvocationID.x;
  if (j >= segments) return;
  elements[2u * j] = lines[2u * sorted[j]];
  elements[2u * j + 1u] = lines[2u * sorted[j] + 1u];
}
