// The exact-OIT resolve, written once against the storage API: load the pixel's list, sort it
// far-to-near with the sort the variant names, blend back to front with "over". Drawn as a
// full-screen triangle with additive blending onto a cleared target: rgb is the composited colour,
// alpha counts how often the pixel was resolved (BMA must resolve each covered pixel exactly once).
//   SORT_IS:  insertion sort in a local array of MAX_FRAGS      (BASE-IS, BMA-IS)
//   SORT_IMS: insertion up to 32 fragments, merge sort above     (BASE-IMS, BMA-IMS)
//   SORT_RBS: register-based block sort, blocks of RBS_M, MAX_K blocks (BASE-RBS-L, BMA-RBS-L)
#include "../common/oitbench.glsl"
#include "storage/linked_list.glsl"

// Early tests: BMA's stencil mask must stop an interval's program before it runs on the other
// intervals' pixels; without this a driver may test the stencil after the shader (it reads
// images and may discard), and every interval pass would cost a full-screen resolve.
layout(early_fragment_tests) in;

uniform vec3 background;
uniform int zero;  // always 0 (fault hooks)
layout(location = 0) out vec4 fragColour;

vec3 blend_over(vec3 c, uvec2 frag) {
  vec4 k = unpackUnorm4x8(frag.x);
  return mix(c, k.rgb, k.a);
}

#if defined(SORT_RBS)
#include "sorts/register_block.glsl"
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
#error "define SORT_IS, SORT_IMS or SORT_RBS"
#endif

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  uint head = FRAG_BEGIN(p);
  if (!FRAG_VALID(head)) discard;
  vec3 c = resolve_pixel(head);
#ifdef OITBENCH_FAULT_WRONG_RESULT
  if (p.x == p.y) c.r += 1.0 / 64.0;  // the diagonal off by 4/255: the validator must notice
#endif
  fragColour = vec4(c + oitbench_fault_hang(zero), 1.0);
}
