// STOCHASTIC's record of the view on the MSAA target (outside the timed passes): every fragment's
// pixel, primitive, sample coverage, colour and depth, which the CPU model needs to draw the same
// masks and run the same per-sample tests.
#include "../common/oitbench.glsl"
#include "../approx/nodes.glsl"
#include "bindings.h"
// The shading of every scene fragment (self-shadowing).
#include "../scene/fragment.glsl"
uniform uint capacity;
uniform int width;
layout(std430, binding = STOCHASTIC_CAPTURE_BINDING) buffer Capture {
  uint count;
  uint words[];
};
// Every fragment, the opaque effect's hidden ones too: the model hides them on the CPU
// (stochastic_case.cpp), so a pass that skips the opaque test disagrees with it.
void main() {
  SceneFragment f = scene_fragment();
  vec4 c = scene_fragment_rgba8(f);
  uint i = atomicAdd(count, 1u);
  if (i < capacity) {
    ivec2 p = ivec2(gl_FragCoord.xy);
    uint b = i * uint(STOCHASTIC_CAPTURE_WORDS);
    words[b] = uint(p.y * width + p.x);
    words[b + 1u] = f.primitive;
    words[b + 2u] = uint(gl_SampleMaskIn[0]);
    words[b + 3u] = packUnorm4x8(c);
    words[b + 4u] = floatBitsToUint(f.depth);
  }
}
