// The full-screen resolve (Brüll 2018, section 4.6, Listing 4.15): composites the pixel's nodes
// front to back and blends the result over the opaque colour (colour: GL_ONE, GL_SRC_ALPHA).
// A pixel without transparent fragments has only empty nodes (alpha 0) and outputs (0, 0, 0, 1):
// the colour stays as it was, so with or without the stencil mask the image is the same; the mask
// only skips the invocations.
//   RESOLVE_BLEND: nodes in storage order (MLAB's array is kept sorted: Table A.4)
//   RESOLVE_SORT:  insertion sort by depth first (UMLAB stores unsorted: Table A.5)
#include "../common/oitbench.glsl"
#include "../storage/storage.glsl"

uniform int zero;  // always 0; unknown to the compiler
layout(location = 0) out vec4 fragColour;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  uvec2 nodes[STORAGE_NODES];
  for (int i = 0; i < STORAGE_NODES; ++i) nodes[i] = STORAGE_LOAD(p, i);
#if defined(RESOLVE_SORT)
  for (int i = 1; i < STORAGE_NODES; ++i) {
    uvec2 key = nodes[i];
    int j = i - 1;
    while (j >= 0 && nodes[j].y > key.y) {
      nodes[j + 1] = nodes[j];
      --j;
    }
    nodes[j + 1] = key;
  }
#elif !defined(RESOLVE_BLEND)
#error "define RESOLVE_BLEND or RESOLVE_SORT"
#endif
  vec3 colour = vec3(0.0);
  float transmittance = 1.0;
  for (int i = 0; i < STORAGE_NODES; ++i) {
    vec4 c = unpackUnorm4x8(nodes[i].x);
    colour += transmittance * c.a * c.rgb;
    transmittance *= 1.0 - c.a;
  }
#ifdef OITBENCH_FAULT_WRONG_RESULT
  // Off by 0.01 at a pixel always inside the coverage and at the top-right one, outside it unless
  // coverage=100: the stencil mask must keep the resolve (and this fault) away from the latter.
  if (p == ivec2(1, 0) || p == ivec2(STORAGE_WIDTH - 1, STORAGE_HEIGHT - 1)) colour.r += 0.01;
#endif
  fragColour = vec4(colour, transmittance) + oitbench_fault_hang(zero);
}
