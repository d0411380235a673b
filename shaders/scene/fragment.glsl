// The one fragment every technique's geometry pass starts from (capture, the approximate, moment,
// wavelet, stochastic, SLAB and peeling passes): scene_fragment() returns it, shaded (shade.glsl), in
// straight alpha, with its depth key, and discards a fragment that has none. What is drawn is not the
// technique's business:
//   mesh     scene.vert's triangles and segments: the vertex colour, soft particles' radial falloff over
//            their uv, the key gl_FragCoord.z
//   SPLATS   Gaussian splats (shaders/splats/: scene.vert's splat path, fragment.glsl): the Gaussian
//            evaluated at the pixel centre, the key the splat_depth parameter selects
// A technique reads the key, never gl_FragCoord.z, so a splat's key reaches every sort, test and weight.
#ifndef OIT_SCENE_FRAGMENT_GLSL
#define OIT_SCENE_FRAGMENT_GLSL
#include "shade.glsl"

struct SceneFragment {
  vec4 colour;       // straight alpha, shaded; full precision (scene_fragment_rgba8: as the capture stores it)
  float depth;       // the depth key in window depth (gl_FragCoord.z's scale)
  float view_depth;  // the same key as a view-space distance along the view axis (frag_depth=view)
  uint primitive;    // which primitive (gl_PrimitiveID for a mesh; 2 x splat + its quad's triangle)
};

#if defined(SPLATS)
#include "../splats/fragment.glsl"
SceneFragment scene_fragment() { return splat_fragment(); }
#else
in vec4 vColour;
in vec2 vUv;
in float vSoft;
in vec3 vWorld;
in float vViewDepth;  // clip w: -z in view space for a perspective projection
SceneFragment scene_fragment() {
  vec4 c = vColour;
  if (vSoft > 0.5) c.a *= clamp(1.0 - dot(vUv, vUv), 0.0, 1.0);  // soft particle: radial falloff
  return SceneFragment(shade_fragment(c, vWorld), gl_FragCoord.z, vViewDepth, uint(gl_PrimitiveID));
}
#endif

// The colour exactly as the capture stores it (RGBA8), so every technique and every CPU model see
// the same fragment.
vec4 scene_fragment_rgba8(SceneFragment f) { return unpackUnorm4x8(packUnorm4x8(f.colour)); }

#endif
