// Stream-split radix sort of line primitives (Sintorn et al., hair poster), step 1: each segment's
// depth slice from its midpoint's view distance. Key 0 is the farthest slice, so sorting keys
// ascending gives back-to-front order.
#include "../common/oitbench.glsl"
layout(local_size_x = 256) in;
struct Vertex { vec4 position; vec4 colour; };
layout(std430, binding = 0) readonly buffer Vertices { Vertex vertices[]; };
layout(std430, binding = 1) writeonly buffer Keys { uint keys[]; };
layout(std430, binding = 2) writeonly buffer Indices { uint indices[]; };
uniform mat4 viewProj;
uniform float nearDistance, farDistance;
uniform uint segments;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= segments) return;
  vec3 mid = 0.5 * (vertices[2 * i].position.xyz + vertices[2 * i + 1].position.xyz);
  float w = (viewProj * vec4(mid, 1.0)).w;  // distance along the view direction
  int slice = clamp(int((w - nearDistance) / (farDistance - nearDistance) * float(SLICES)), 0, SLICES - 1);
  keys[i] = uint(SLICES - 1 - slice);
  indices[i] = i;
}
