// The viewer shows a case's result: colour where a resolve wrote (alpha > 0), the backdrop where
// no fragment landed (alpha == 0: the scene's background, or with the opaque effect the opaque
// pass's colour), nearest texel when the window is resized.
#include "../common/oitbench.glsl"
#include "bindings.h"
layout(binding = PRESENT_IMAGE_UNIT) uniform sampler2D image;
layout(binding = PRESENT_OPAQUE_UNIT) uniform sampler2D opaqueImage;
uniform bool hasOpaque;
uniform vec3 background;
uniform vec2 texelsPerPixel;
out vec4 colour;
void main() {
  ivec2 p = min(ivec2(gl_FragCoord.xy * texelsPerPixel), textureSize(image, 0) - 1);
  vec4 c = texelFetch(image, p, 0);
  vec3 behind = hasOpaque ? texelFetch(opaqueImage, p, 0).rgb : background;
  colour = vec4(c.a > 0.0 ? c.rgb : behind, 1.0);
}
