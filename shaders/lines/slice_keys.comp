// Stream-split radix sort of primitives (Sintorn et al., hair poster), step 1: each primitive's
// depth slice from its centre's view distance. Key 0 is the farthest slice, so sorting keys
// ascending gives back-to-front order. Primitive i is the PRIMITIVE_VERTICES (2: a line segment,
// the default and the lines experiment's; 3: a triangle, the self-shadowing map's,
// micro/oit/scene/shadow_map.cpp) indices at PRIMITIVE_VERTICES * i (Mesh::line_indices, Mesh::indices)
// into the scene mesh's oit::Vertex records of VERTEX_FLOATS floats, the position first.
#include "../common/oitbench.glsl"
#include "bindings.h"
#ifndef PRIMITIVE_VERTICES
#define PRIMITIVE_VERTICES 2
#endif
layout(local_size_x = 256) in;
layout(std430, binding = SLICE_KEYS_VERTICES_BINDING) readonly buffer Vertices { float vertexFloats[]; };
layout(std430, binding = SLICE_KEYS_KEYS_BINDING) writeonly buffer Keys { uint keys[]; };
layout(std430, binding = SLICE_KEYS_INDICES_BINDING) writeonly buffer Indices { uint indices[]; };
layout(std430, binding = SLICE_KEYS_PRIMITIVES_BINDING) readonly buffer PrimitiveIndices { uint primitiveIndices[]; };
uniform mat4 viewProj;
uniform float nearDistance, farDistance;
uniform uint segments;

vec3 primitive_centre(uint i) {
  vec3 sum = vec3(0.0);
  for (uint k = 0u; k < uint(PRIMITIVE_VERTICES); ++k) {
    uint v = primitiveIndices[uint(PRIMITIVE_VERTICES) * i + k] * uint(VERTEX_FLOATS);
    sum += vec3(vertexFloats[v], vertexFloats[v + 1u], vertexFloats[v + 2u]);
  }
  return sum / float(PRIMITIVE_VERTICES);
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= segments) return;
  vec3 mid = primitive_centre(i);
  float w = (viewProj * vec4(mid, 1.0)).w;  // distance along the view direction
  int slice = clamp(int((w - nearDistance) / (farDistance - nearDistance) * float(SLICES)), 0, SLICES - 1);
  keys[i] = uint(SLICES - 1 - slice);
  indices[i] = i;
}
