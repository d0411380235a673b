// resolve_pixel(head): the exact-OIT resolve of one pixel, shared by the fragment-shader resolve
// (resolve.frag) and the compute one (resolve.comp): load the pixel's list, sort it far-to-near
// with the sort the variant names, blend back to front with "over" onto `background`.
//   SORT_IS:    insertion sort in a local array of MAX_FRAGS       (BASE-IS, BMA-IS, CS-IS)
//   SORT_IMS:   insertion up to 32 fragments, merge sort above      (BASE-IMS, BMA-IMS, CS-IMS)
//   SORT_RBS:   register-based block sort, blocks of RBS_M, MAX_K blocks merged from local memory
//               (BASE-RBS-L, BMA-RBS-L, CS-RBS-L)
//   SORT_RBS_G: the same blocks sorted in place in the list's nodes, merged from global memory (RBS-G)
// Expects: a storage include, `uniform vec3 background`.

vec3 blend_over(vec3 c, uvec2 frag) {
  vec4 k = unpackUnorm4x8(frag.x);
  return mix(c, k.rgb, k.a);
}

// The shader library expands each include once, at its first #include, whatever the #if around
// it: the register half both RBS variants share must come first, under a condition true for both.
#if defined(SORT_RBS) || defined(SORT_RBS_G)
#include "sorts/register_sort.glsl"
#endif

#if defined(SORT_RBS)
#include "sorts/register_block.glsl"
#elif defined(SORT_RBS_G)
#include "sorts/register_block_global.glsl"
#elif defined(SORT_IS) || defined(SORT_IMS)
uvec2 frags[MAX_FRAGS];
#include "sorts/insertion.glsl"
#if defined(SORT_IMS) && MAX_FRAGS > 32
#include "sorts/merge.glsl"
#endif
vec3 resolve_pixel(uint node) {
  int n = 0;
  while (FRAG_VALID(node) && n < MAX_FRAGS) {  // deeper pixels are truncated (counted on the host)
    frags[n++] = FRAG_LOAD(node);
    node = FRAG_NEXT(node);
  }
#if defined(SORT_IMS) && MAX_FRAGS > 32
  if (n > 32) sort_merge(n);
  else
#endif
  sort_insertion(n);
  vec3 c = background;
  for (int i = 0; i < n; ++i) c = blend_over(c, frags[i]);
  return c;
}
#else
#error "define SORT_IS, SORT_IMS, SORT_RBS or SORT_RBS_G"
#endif
