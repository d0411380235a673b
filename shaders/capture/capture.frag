// Fragment capture into per-pixel linked lists: every fragment of every primitive is stored.
// Early fragment tests keep the atomics of fragments an opaque depth test would reject from running.
#include "../common/oitbench.glsl"
#define STORAGE_CAPTURE
#include "fragment_storage.glsl"
#include "../scene/shade.glsl"
layout(early_fragment_tests) in;
in vec4 vColour;
in vec2 vUv;
in float vSoft;
in vec3 vWorld;
in float vViewDepth;  // frag_depth=view: the view-space distance along the view axis
void main() {
  vec4 c = vColour;
  if (vSoft > 0.5) c.a *= clamp(1.0 - dot(vUv, vUv), 0.0, 1.0);  // soft particle: radial falloff
#ifdef FRAG_DEPTH_VIEW
  store_fragment(ivec2(gl_FragCoord.xy), shade_fragment(c, vWorld), vViewDepth);
#else
  store_fragment(ivec2(gl_FragCoord.xy), shade_fragment(c, vWorld), gl_FragCoord.z);
#endif
}
