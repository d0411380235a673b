// The light's transmittance at a world position, read from the opacity shadow map that
// micro/oit/scene/shadow_map.cpp builds and binds (OpacityShadowMap::bind): the map's layers are the
// optical depth in front of each slice boundary, interpolated linearly between boundaries (and
// bilinearly across texels) by the 3D texture's filter. Outside the light's frustum: fully lit.
// The caller applies the ambient floor (shaders/scene/shade.glsl).
#ifndef OITBENCH_SHADOW_TRANSMITTANCE_GLSL
#define OITBENCH_SHADOW_TRANSMITTANCE_GLSL
#include "bindings.h"

layout(binding = SHADOW_MAP_UNIT) uniform sampler3D shadowMap;
uniform mat4 shadowViewProj;
uniform vec2 shadowRange;  // the light-view distances the slices divide: near, far

float shadow_transmittance(vec3 world) {
  vec4 clip = shadowViewProj * vec4(world, 1.0);
  if (clip.w <= 0.0) return 1.0;
  vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return 1.0;
  float layers = float(textureSize(shadowMap, 0).z);  // SLICES + 1 boundaries
  float s = clamp((clip.w - shadowRange.x) / (shadowRange.y - shadowRange.x), 0.0, 1.0) * (layers - 1.0);
  return exp(-texture(shadowMap, vec3(uv, (s + 0.5) / layers)).r);
}

#endif
