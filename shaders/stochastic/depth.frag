// STOCHASTIC pass 1 (per MSAA pass): the fragment covers the samples of its alpha-drawn mask, and
// the depth test (less, writing) keeps the nearest covering surface per sample. The fragment's
// depth is written for all its samples (gl_FragDepth), the same value the accumulation tests.
#include "../common/oitbench.glsl"
#include "../approx/nodes.glsl"
#include "hash.glsl"
// The scene effects: the opaque depth tested here (opaque_hides), the shading (self-shadowing).
#include "../scene/backdrop.glsl"
#include "../scene/fragment.glsl"
uniform uint frameSeed;
uniform uint passIndex;
void main() {
  SceneFragment f = scene_fragment();
  if (opaque_hides(ivec2(gl_FragCoord.xy), f.depth)) discard;
  vec4 c = scene_fragment_rgba8(f);
  uint alpha_byte = packUnorm4x8(c) >> 24;
  gl_SampleMask[0] = int(stochastic_mask(frameSeed, passIndex, uvec2(gl_FragCoord.xy), f.primitive, alpha_byte,
                                         uint(MSAA_SAMPLES)));
  gl_FragDepth = f.depth;
}
