// The viewer shows a case's result: colour where a resolve wrote (alpha > 0), the scene's
// background where no fragment landed (alpha == 0), nearest texel when the window is resized.
#include "../common/oitbench.glsl"
layout(binding = 0) uniform sampler2D image;
uniform vec3 background;
uniform vec2 texelsPerPixel;
out vec4 colour;
void main() {
  ivec2 p = min(ivec2(gl_FragCoord.xy * texelsPerPixel), textureSize(image, 0) - 1);
  vec4 c = texelFetch(image, p, 0);
  colour = vec4(c.a > 0.0 ? c.rgb : background, 1.0);
}
