// The full-screen resolve (Brüll 2018, section 4.6, Listing 4.15): composites the pixel's nodes
// front to back and blends the result over the opaque colour (colour: GL_ONE, GL_SRC_ALPHA).
// A pixel without transparent fragments has only empty nodes (alpha 0) and outputs (0, 0, 0, 1):
// the colour stays as it was, so with or without the stencil mask the image is the same; the mask
// only skips the invocations.
//   RESOLVE_BLEND: nodes in storage order (MLAB's array is kept sorted: Table A.4)
//   RESOLVE_SORT:  insertion sort by depth first (UMLAB stores unsorted: Table A.5): the sort
//                  library's shaders/sorts/insertion.glsl (Listing 4.11, the direct write), bound
//                  here to the nodes, ascending by their depth key .y, in registers (constant bounds)
#include "../common/oitbench.glsl"
#include "../storage/storage.glsl"
#include "../sorts/api.glsl"

uniform int zero;  // always 0; unknown to the compiler
layout(location = 0) out vec4 fragColour;

// A global, so the library's sort can name it (the binding of shaders/sorts/api.glsl).
uvec2 nodes[STORAGE_NODES];

#if defined(RESOLVE_SORT)
#define SORT_T uvec2
#define SORT_AT(i) nodes[i]
#define SORT_GT(a, b) ((a).y > (b).y)
#define SORT_N STORAGE_NODES
#define SORT_SIZE STORAGE_NODES
#include "../sorts/insertion.glsl"
#elif !defined(RESOLVE_BLEND)
#error "define RESOLVE_BLEND or RESOLVE_SORT"
#endif

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  for (int i = 0; i < STORAGE_NODES; ++i) nodes[i] = STORAGE_LOAD(p, i);
#if defined(RESOLVE_SORT)
  sort_insertion();
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
