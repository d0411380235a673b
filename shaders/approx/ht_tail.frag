// Pass 2 of HT (hybrid transparency, Maule et al. 2013): the fragments behind the core's n-th
// node (a full core's last, in (depth, colour) order) are the tail, accumulated order-independently
// by additive blending: (sum C_i a_i, sum a_i) into attachment 0 and their count into attachment 1,
// the weighted average the resolve composites behind the core.
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
  if (!tail) discard;
  accumOut = vec4(c.rgb * c.a, c.a);
  countOut = 1.0;
}
