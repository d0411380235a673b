// SLAB's resolve: each sample shows the layer whose mask holds it, or the backdrop where none does;
// the pixel is their average.
#include "../common/oitbench.glsl"
#include "bindings.h"
#include "../scene/backdrop.glsl"
uniform int width;
uniform int zero;
layout(std430, binding = SLAB_LAYERS_BINDING) readonly buffer Layers { uint words[]; };
layout(location = 0) out vec4 fragColour;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  uint base = uint(p.y * width + p.x) * uint(SLAB_LAYERS * SLAB_LAYER_WORDS);
  vec3 c = vec3(0.0);
  int covered = 0;
  for (int i = 0; i < SLAB_LAYERS; ++i) {
    uint b = base + uint(i * SLAB_LAYER_WORDS);
    int n = bitCount(words[b + 1u]);
    c += unpackUnorm4x8(words[b + 2u]).rgb * float(n);
    covered += n;
  }
  c = (c + backdrop_colour(p) * float(SLAB_SAMPLES - covered)) / float(SLAB_SAMPLES);
#ifdef OITBENCH_FAULT_WRONG_RESULT
  if (p.x == p.y) c.r += 1.0 / 16.0;
#endif
  fragColour = vec4(c + oitbench_fault_hang(zero), 1.0);
}
