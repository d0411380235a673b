// What a fragment casts into the opacity shadow map: its alpha as shaders/capture/capture.frag computes
// it (soft billboards' radial falloff), rounded to the 8 bits the validation's light capture keeps
// (so the CPU map sums the same values), and its optical depth -log(1 - alpha), which adds up
// along a ray where alphas multiply.
#ifndef OITBENCH_SHADOW_OPACITY_GLSL
#define OITBENCH_SHADOW_OPACITY_GLSL
#include "bindings.h"

float shadow_alpha(vec4 colour, vec2 uv, float soft) {
  float a = colour.a;
  if (soft > 0.5) a *= clamp(1.0 - dot(uv, uv), 0.0, 1.0);
  return floor(clamp(a, 0.0, 1.0) * 255.0 + 0.5) / 255.0;
}

float optical_depth(float alpha) { return -log(1.0 - min(alpha, SHADOW_MAX_ALPHA)); }

#endif
