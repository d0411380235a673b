// The splat list on the GPU (micro/oit/splats/gpu_splats.cpp writes it): SPLAT_WORDS vec4s a splat.
#ifndef OIT_SPLATS_SPLATS_GLSL
#define OIT_SPLATS_SPLATS_GLSL
#include "bindings.h"
#include "project.glsl"

layout(std430, binding = SPLATS_BINDING) readonly buffer Splats { vec4 splatWords[]; };

struct Splat {
  vec3 position;
  float opacity;
  vec3 scale;
  vec4 rotation;  // (w, x, y, z)
  vec3 colour;
};

Splat load_splat(uint i) {
  uint b = i * uint(SPLAT_WORDS);
  vec4 po = splatWords[b], s = splatWords[b + 1u];
  return Splat(po.xyz, po.w, s.xyz, splatWords[b + 2u], splatWords[b + 3u].rgb);
}

#endif
