// WOIT pass 1: every fragment adds its absorbance -ln(1 - alpha) times each basis function at its
// warped depth (additive blending into WAVELET_TARGETS layers of RGBA, 32- or 16-bit float).
#include "../common/oitbench.glsl"
#include "../approx/nodes.glsl"
#include "wavelet_math.glsl"
// The scene effects: the opaque depth tested here (opaque_hides), the shading (self-shadowing).
#include "../scene/backdrop.glsl"
#include "../scene/fragment.glsl"
uniform vec2 nearFar;
uniform vec2 depthRange;  // the view depths the warp maps to [0, 1)
uniform int zero;
layout(location = 0) out vec4 coeffs0;
layout(location = 1) out vec4 coeffs1;
#if WAVELET_TARGETS > 2
layout(location = 2) out vec4 coeffs2;
layout(location = 3) out vec4 coeffs3;
#endif
#if WAVELET_TARGETS > 4
layout(location = 4) out vec4 coeffs4;
layout(location = 5) out vec4 coeffs5;
layout(location = 6) out vec4 coeffs6;
layout(location = 7) out vec4 coeffs7;
#endif
#define COEFFS_AT(i) vec4(w[4 * i], w[4 * i + 1], w[4 * i + 2], w[4 * i + 3])
void main() {
  SceneFragment f = scene_fragment();
  if (opaque_hides(ivec2(gl_FragCoord.xy), f.depth)) discard;
  vec4 c = scene_fragment_rgba8(f);
  float a = c.a >= 1.0 ? ABSORBANCE_MAX : min(-log(1.0 - c.a), ABSORBANCE_MAX);
  float w[WAVELET_COEFFS];
  basis_contribution(wavelet_warp(f.depth, nearFar, depthRange), a, w);
  coeffs0 = COEFFS_AT(0) + vec4(oitbench_fault_hang(zero));
  coeffs1 = COEFFS_AT(1);
#if WAVELET_TARGETS > 2
  coeffs2 = COEFFS_AT(2);
  coeffs3 = COEFFS_AT(3);
#endif
#if WAVELET_TARGETS > 4
  coeffs4 = COEFFS_AT(4);
  coeffs5 = COEFFS_AT(5);
  coeffs6 = COEFFS_AT(6);
  coeffs7 = COEFFS_AT(7);
#endif
}
