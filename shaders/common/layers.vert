// `layers` overlapping screen-filling quads in one draw: glDrawArrays(GL_TRIANGLES, 0, 6 * layers),
// no vertex buffer. Each quad is two triangles, so the shared diagonal cuts 2x2 pixel quads and
// produces helper invocations there (as real geometry does), while the fill rule still covers
// every pixel exactly once per layer. `coverageTop` (NDC) cuts the quads to a band [-1, top].
#include "oitbench.glsl"

uniform float coverageTop = 1.0;
flat out int layer;

void main() {
  const vec2 corners[6] = vec2[6](vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1), vec2(1, 1), vec2(-1, 1));
  vec2 c = corners[gl_VertexID % 6];
  layer = gl_VertexID / 6;
  gl_Position = vec4(c.x, c.y > 0.0 ? coverageTop : -1.0, 0.0, 1.0);
}
