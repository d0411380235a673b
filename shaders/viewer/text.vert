// The viewer's overlay text: positions in framebuffer pixels from the top-left corner.
#include "../common/oitbench.glsl"
layout(location = 0) in vec2 position;
layout(location = 1) in vec4 colour;
uniform vec2 viewportSize;
out vec4 vColour;
void main() {
  vec2 ndc = position / viewportSize * 2.0 - 1.0;
  gl_Position = vec4(ndc.x, -ndc.y, 0.0, 1.0);
  vColour = colour;
}
