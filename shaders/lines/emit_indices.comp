// The sorted primitive order as an element buffer for one draw (GL_LINES, or GL_TRIANGLES for the
// self-shadowing map): the sorted primitives' own PRIMITIVE_VERTICES indices (as in slice_keys.comp).
#include "../common/oitbench.glsl"
#include "bindings.h"
#ifndef PRIMITIVE_VERTICES
#define PRIMITIVE_VERTICES 2
#endif
layout(local_size_x = 256) in;
layout(std430, binding = EMIT_SORTED_BINDING) readonly buffer Sorted { uint sorted[]; };
layout(std430, binding = EMIT_ELEMENTS_BINDING) writeonly buffer Elements { uint elements[]; };
layout(std430, binding = EMIT_PRIMITIVES_BINDING) readonly buffer PrimitiveIndices { uint primitiveIndices[]; };
uniform uint segments;
void main() {
  uint j = gl_GlobalInvocationID.x;
  if (j >= segments) return;
  for (uint k = 0u; k < uint(PRIMITIVE_VERTICES); ++k)
    elements[uint(PRIMITIVE_VERTICES) * j + k] = primitiveIndices[uint(PRIMITIVE_VERTICES) * sorted[j] + k];
}
