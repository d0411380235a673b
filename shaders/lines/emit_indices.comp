// The sorted segment order as an element buffer for one GL_LINES draw. INDEXED_PRIMITIVES (as in
// slice_keys.comp): the sorted primitives' own PRIMITIVE_VERTICES indices, for GL_LINES or GL_TRIANGLES.
#include "../common/oitbench.glsl"
layout(local_size_x = 256) in;
layout(std430, binding = 0) readonly buffer Sorted { uint sorted[]; };
layout(std430, binding = 1) writeonly buffer Elements { uint elements[]; };
#ifdef INDEXED_PRIMITIVES
layout(std430, binding = 2) readonly buffer PrimitiveIndices { uint primitiveIndices[]; };
#endif
uniform uint segments;
void main() {
  uint j = gl_GlobalInvocationID.x;
  if (j >= segments) return;
#ifdef INDEXED_PRIMITIVES
  for (uint k = 0u; k < uint(PRIMITIVE_VERTICES); ++k)
    elements[uint(PRIMITIVE_VERTICES) * j + k] = primitiveIndices[uint(PRIMITIVE_VERTICES) * sorted[j] + k];
#else
  elements[2u * j] = 2u * sorted[j];
  elements[2u * j + 1u] = 2u * sorted[j] + 1u;
#endif
}
