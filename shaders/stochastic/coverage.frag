// STOCHASTIC's record of the view on the MSAA target (outside the timed passes): every fragment's
// pixel, primitive, sample coverage, colour and depth, which the CPU model needs to draw the same
// masks and run the same per-sample tests.
#include "../common/oitbench.glsl"
#include "../approx/nodes.glsl"
#include "bindings.h"
// The shading of every scene fragment (self-shadowing).
#include "../scene/shade.glsl"
in vec4 vColour;
in vec3 vWorld;
in vec2 vUv;
in float vSoft;
uniform uint capacity;
uniform int width;
layout(std430, binding = STOCHASTIC_CAPTURE_BINDING) buffer Capture {
  uint count;
  uint words[];
};
// Every fragment, the opaque effect's hidden ones too: the model hides them on the CPU
// (stochastic_case.cpp), so a pass that skips the opaque test disagrees with it.
void main() {
  vec4 c = approx_fragment_colour(shade_fragment(vColour, vWorld), vUv, vSoft);
  uint i = atomicAdd(count, 1u);
  if (i < capacity) {
    ivec2 p = ivec2(gl_FragCoord.xy);
    uint b = i * uint(STOCHASTIC_CAPTURE_WORDS);
    words[b] = uint(p.y * width + p.x);
    words[b + 1u] = uint(gl_PrimitiveID);
    words[b + 2u] = uint(gl_SampleMaskIn[0]);
    words[b + 3u] = packUnorm4x8(c);
    words[b + 4u] = floatBitsToUint(gl_FragCoord.z);
  }
}
