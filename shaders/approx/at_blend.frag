// Pass 2 of the AT family: every fragment adds its contribution alpha * c * vis(z) (Eq. 2.4) to
// an additive RGBA32F accumulation (in submission order per pixel on a serial rasteriser); alpha
// accumulates alpha * vis(z), the opacity the resolve checks the colour against.
#include "../common/oitbench.glsl"
#include "../storage/storage.glsl"
#include "visibility.glsl"
#include "../scene/fragment.glsl"
layout(location = 0) out vec4 fragColour;
void main() {
  SceneFragment f = scene_fragment();
  vec4 c = scene_fragment_rgba8(f);
  float w = c.a * visibility(ivec2(gl_FragCoord.xy), f.depth);
  fragColour = vec4(c.rgb * w, w);
}
