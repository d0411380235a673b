// Fragment capture into per-pixel linked lists: every fragment of every primitive is stored.
// Early fragment tests keep the atomics of fragments an opaque depth test would reject from running.
// The fragment and its depth key come from the scene (shaders/scene/fragment.glsl: a mesh's, or a
// splat's Gaussian with its splat_depth key, which needs no gl_FragDepth: the key is stored).
#include "../common/oitbench.glsl"
#define STORAGE_CAPTURE
#include "fragment_storage.glsl"
#include "../scene/fragment.glsl"
layout(early_fragment_tests) in;
void main() {
  SceneFragment f = scene_fragment();
#ifdef FRAG_DEPTH_VIEW
  store_fragment(ivec2(gl_FragCoord.xy), f.colour, f.view_depth);  // the view-space distance along the view axis
#else
  store_fragment(ivec2(gl_FragCoord.xy), f.colour, f.depth);
#endif
}
