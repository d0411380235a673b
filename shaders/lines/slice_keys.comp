// Stream-split radix sort of line primitives (Sintorn et al., hair poster), step 1: each segment's
// depth slice from its midpoint's view distance. Key 0 is the farthest slice, so sorting keys
// ascending gives back-to-front order.
// INDEXED_PRIMITIVES (the self-shadowing map, micro/oit/shadow_map.cpp): primitive i is the
// PRIMITIVE_VERTICES (2: a line, 3: a triangle) indices at PRIMITIVE_VERTICES * i into oit::Vertex
// records of VERTEX_FLOATS floats (position first), and its key comes from their centroid.
#include "../common/oitbench.glsl"
layout(local_size_x = 256) in;
#ifdef INDEXED_PRIMITIVES
layout(std430, binding = 0) readonly buffer Vertices { float vertexFloats[]; };
layout(std430, binding = 3) readonly buffer PrimitiveIndices { uint primitiveIndices[]; };
vec3 primitive_centre(uint i) {
  vec3 sum = vec3(0.0);
  for (uint k = 0u; k < uint(PRIMITIVE_VERTICES); ++k) {
    uint v = primitiveIndices[uint(PRIMITIVE_VERTICES) * i + k] * uint(VERTEX_FLOATS);
    sum += vec3(vertexFloats[v], vertexFloats[v + 1u], vertexFloats[v + 2u]);
  }
  return sum / float(PRIMITIVE_VERTICES);
}
#else
struct Vertex { vec4 position; vec4 colour; };
layout(std430, binding = 0) readonly buffer Vertices { Vertex vertices[]; };
vec3 primitive_centre(uint i) { return 0.5 * (vertices[2 * i].position.xyz + vertices[2 * i + 1].position.xyz); }
#endif
layout(std430, binding = 1) writeonly buffer Keys { uint keys[]; };
layout(std430, binding = 2) writeonly buffer Indices { uint indices[]; };
uniform mat4 viewProj;
uniform float nearDistance, farDistance;
uniform uint segments;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= segments) return;
  vec3 mid = primitive_centre(i);
  float w = (viewProj * vec4(mid, 1.0)).w;  // distance along the view direction
  int slice = clamp(int((w - nearDistance) / (farDistance - nearDistance) * float(SLICES)), 0, SLICES - 1);
  keys[i] = uint(SLICES - 1 - slice);
  indices[i] = i;
}
