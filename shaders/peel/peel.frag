// Depth peeling, front to back (DP, Everitt 2001), or from both ends at once (DDP, dual depth
// peeling, Bavoil & Myers 2008: DUAL), with an exact tie rule. One program, two geometry passes
// per iteration (the same program, so every pass computes the same gl_FragCoord.z bit for bit):
//   peelPass 0, peel: blends the fragments of the layers found last iteration (front: "under" into
//     attachment 0; DUAL back: "over" into attachment 1) and finds the depths of the next ones
//     among the fragments strictly between them: MAX blending of (-z, z) into the min-max target
//     (the paper's RG32F MAX blend; DP uses only its first channel).
//   peelPass 1, tie: among those fragments, the ones at the new front depth take the smallest
//     colour key (imageAtomicMin), those at the new back depth the largest (imageAtomicMax). The
//     occlusion query around this pass counts the fragments of the new layers: 0 ends the peel.
// A layer is a (depth, colour key) pair, the key being the fragment's RGBA8 colour bits: the order
// the exact reference and every exact resolve composite equal depths in (by colour). Fragments with
// the same depth and the same colour are one layer and blend together (in any order: they are
// equal). Classic peeling compares depth only (TIE_RULE_DEPTH, the tie_rule=depth variant): of
// fragments at one depth only the smallest colour survives, the others are lost.
#include "../common/oitbench.glsl"
#include "../approx/nodes.glsl"
#include "bindings.h"
// The scene effects: the opaque effect's depth tested here (the peel has its own depth targets, so
// not by a depth buffer: a fragment behind the opaque surface is discarded before anything), and the
// shading of every scene fragment (self-shadowing).
#include "../scene/backdrop.glsl"
#include "../scene/fragment.glsl"
uniform int peelPass;
uniform int zero;
layout(binding = PEEL_PREV_MINMAX_UNIT) uniform sampler2D prevMinMax;
layout(binding = PEEL_NEXT_MINMAX_UNIT) uniform sampler2D nextMinMax;
layout(r32ui, binding = PEEL_PREV_FRONT_IMAGE) readonly uniform uimage2D prevFront;
layout(r32ui, binding = PEEL_NEXT_FRONT_IMAGE) uniform uimage2D nextFront;
#if defined(DUAL)
layout(r32ui, binding = PEEL_PREV_BACK_IMAGE) readonly uniform uimage2D prevBack;
layout(r32ui, binding = PEEL_NEXT_BACK_IMAGE) uniform uimage2D nextBack;
layout(location = 0) out vec4 frontOut;
layout(location = 1) out vec4 backOut;
layout(location = 2) out vec2 minMaxOut;
#else
layout(location = 0) out vec4 frontOut;
layout(location = 1) out vec2 minMaxOut;
#endif

// (za, ka) strictly before (zb, kb) in the peel order.
bool before(float za, uint ka, float zb, uint kb) {
#if defined(TIE_RULE_DEPTH)
  return za < zb;
#else
  return za < zb || (za == zb && ka < kb);
#endif
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  SceneFragment f = scene_fragment();
  if (opaque_hides(p, f.depth)) discard;
  vec4 c = scene_fragment_rgba8(f);
  uint key = packUnorm4x8(c);
  float z = f.depth;
  vec2 prev = texelFetch(prevMinMax, p, 0).xy;
  float frontZ = -prev.x;
  uint frontKey = imageLoad(prevFront, p).x;
#if defined(DUAL)
  float backZ = prev.y;
  uint backKey = imageLoad(prevBack, p).x;
#else
  float backZ = 2.0;  // behind every fragment
  uint backKey = 0u;
#endif
  bool between = before(frontZ, frontKey, z, key) && before(z, key, backZ, backKey);
  if (peelPass == 0) {
    vec4 premultiplied = vec4(c.rgb * c.a, c.a);
    bool isFront = z == frontZ && key == frontKey;
    frontOut = isFront ? premultiplied : vec4(0.0);
#if defined(DUAL)
    backOut = !isFront && z == backZ && key == backKey ? premultiplied : vec4(0.0);
#endif
    minMaxOut = between ? vec2(-z, z) : vec2(-2.0);
  } else {
    vec2 next = texelFetch(nextMinMax, p, 0).xy;
    bool hit = false;
    if (between && z == -next.x) {
      imageAtomicMin(nextFront, p, key);
      hit = true;
    }
#if defined(DUAL)
    if (between && z == next.y) {
#if defined(TIE_RULE_DEPTH)
      imageAtomicMin(nextBack, p, key);  // by depth alone the smallest colour survives at either end
#else
      imageAtomicMax(nextBack, p, key);
#endif
      hit = true;
    }
#endif
    if (!hit) discard;  // the occlusion query counts the fragments of the new layers
    frontOut = vec4(oitbench_fault_hang(zero));
  }
}
