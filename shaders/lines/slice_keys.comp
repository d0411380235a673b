// Stream-split radix sort of line primitives (Sintorn et al., hair poster), step 1: each segment's
// depth slice from its midpoint's view distance. Key 0 is the farthest slice, so sorting keys
// ascending gives back-to-front order. The vertices are the scene mesh's (micro/oit/scene.hpp's
// Vertex, VERTEX_FLOATS floats each, the position first); segment i joins vertices lines[2i] and
// lines[2i + 1] (Mesh::line_indices).
#include "../common/oitbench.glsl"
layout(local_size_x = 256) in;
layout(std430, binding = 0) readonly buffer Vertices { float vertexData[]; };
layout(std430, binding = 1) writeonly buffer Keys { uint keys[]; };
layout(std430, binding = 2) writeonly buffer Indices { uint indices[]; };
layout(std430, binding = 3) readonly buffer Lines { uint lines[]; };
uniform mat4 viewProj;
uniform float nearDistance, farDistance;
uniform uint segments;

vec3 vertex_position(uint v) {
  uint at = v * uint(VERTEX_FLOATS);
  return vec3(vertexData[at], vertexData[at + 1u], vertexData[at + 2u]);
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= segments) return;
  vec3 mid = 0.5 * (vertex_position(lines[2u * i]) + vertex_position(lines[2u * i + 1u]));
  float w = (viewProj * vec4(mid, 1.0)).w;  // distance along the view direction
  int slice = clamp(int((w - nearDistance) / (farDistance - nearDistance) * float(SLICES)), 0, SLICES - 1);
  keys[i] = uint(SLICES - 1 - slice);
  indices[i] = i;
}
