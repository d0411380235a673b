// WOIT pass 2: every fragment adds its premultiplied colour and alpha weighted by exp(-A), A the
// absorbance its pixel's coefficients reconstruct in front of its depth (additive, RGBA32F).
#include "../common/oitbench.glsl"
#include "../approx/nodes.glsl"
#include "bindings.h"
#include "wavelet_math.glsl"
// The scene effects: the opaque depth tested here (opaque_hides), the shading (self-shadowing).
#include "../scene/backdrop.glsl"
#include "../scene/fragment.glsl"
uniform vec2 nearFar;
uniform vec2 depthRange;  // the view depths the warp maps to [0, 1)
layout(binding = WAVELETS_COEFFS_UNIT) uniform sampler2DArray coefficients;
layout(location = 0) out vec4 weighted;
void main() {
  SceneFragment f = scene_fragment();
  if (opaque_hides(ivec2(gl_FragCoord.xy), f.depth)) discard;
  vec4 c = scene_fragment_rgba8(f);
  ivec2 px = ivec2(gl_FragCoord.xy);
  float w[WAVELET_COEFFS];
  for (int t = 0; t < WAVELET_TARGETS; ++t) {
    vec4 v = texelFetch(coefficients, ivec3(px, t), 0);
    w[4 * t] = v.x;
    w[4 * t + 1] = v.y;
    w[4 * t + 2] = v.z;
    w[4 * t + 3] = v.w;
  }
  float t = exp(-basis_absorbance(w, wavelet_warp(f.depth, nearFar, depthRange)));
  weighted = vec4(c.rgb * c.a * t, c.a * t);
}
