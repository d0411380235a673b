// Pass 2 of HT (hybrid transparency, Maule et al. 2013): the fragments behind the core's n-th
// node (a full core's last, in (depth, colour) order) are the tail, accumulated order-independently
// by additive blending: (sum C_i a_i, sum a_i) into attachment 0 and their count into attachment 1,
// the weighted average the resolve composites behind the core.
// HT_HTGS (HTGS's HYBRID_BLEND, Hahlbohm et al. 2025): the fragments below HTGS_CORE_ALPHA join the tail
// too, and attachment 1 (cleared to 1, blended (zero, 1 - src)) takes the product of their transmittances,
// the coverage the resolve gives the tail instead of Maule's 1 - (1 - a_avg)^n.
#include "../common/oitbench.glsl"
#include "../storage/storage.glsl"
#include "nodes.glsl"
#include "../scene/fragment.glsl"
layout(location = 0) out vec4 accumOut;
layout(location = 1) out float countOut;
void main() {
  SceneFragment f = scene_fragment();
  vec4 c = scene_fragment_rgba8(f);
  uint key = packUnorm4x8(c);
  float z = f.depth;
  uvec2 last = STORAGE_LOAD(ivec2(gl_FragCoord.xy), N - 1);
  float lastZ = node_depth(last);
  bool tail = lastZ != DEPTH_EMPTY && (z > lastZ || (z == lastZ && key > last.x));
#if defined(HT_HTGS)
  tail = tail || c.a < HTGS_CORE_ALPHA;
#endif
  if (!tail) discard;
  accumOut = vec4(c.rgb * c.a, c.a);
#if defined(HT_HTGS)
  countOut = c.a;
#else
  countOut = 1.0;
#endif
}
