// resolve_pixel(head): the exact-OIT resolve of one pixel, shared by the fragment-shader resolve
// (resolve.frag) and the compute one (resolve.comp): load the pixel's list, sort it far-to-near
// with the sort the variant names, blend back to front with "over" onto `backdrop`. The sorts
// are the library's (shaders/sorts/), the same files the sort experiment times:
//   SORT_ORDER_CHECK (IS, IMS): a list already far-to-near is not sorted, one near-to-far is
//               reversed in O(n) (the order_check parameter)
//   SORT_IS:    insertion sort (sorts/insertion.glsl) in a local array of MAX_FRAGS
//               (BASE-IS, BMA-IS, CS-IS)
//   SORT_IMS:   insertion up to 32 fragments, merge sort above (sorts/merge.glsl, its
//               SORT_MERGE_HALF_SCRATCH form, injected by micro/oit/resolve/resolve_sort.cpp)
//               (BASE-IMS, BMA-IMS, CS-IMS)
//   SORT_RBS:   register-based block sort, blocks of RBS_M sorted by the RS network
//               (sorts/register_sort.glsl), MAX_K blocks merged from local memory (rbs.glsl)
//               (BASE-RBS-L, BMA-RBS-L, CS-RBS-L)
//   SORT_RBS_G: the same blocks sorted in place in the list's nodes, merged from global memory
//               (rbs.glsl) (RBS-G)
// micro/oit/resolve/resolve_sort.cpp names the same files for the `sort_source` column.
//   EARLY_STOP (IS, IMS, RBS-L; the early_stop parameter, a float threshold): 3DGS's early termination (Kerbl
//               et al. 2023): the sorted fragments composited front to back ("under"), stopping at the
//               fragment that would take the transmittance below EARLY_STOP (not blended, nor any after it)
// Expects: a storage include, `vec3 backdrop` (set per pixel from backdrop.glsl's backdrop_colour()).

vec3 blend_over(vec3 c, FRAG_T frag) {
  vec4 k = frag_colour(frag);
  return mix(c, k.rgb, k.a);
}

#if defined(EARLY_STOP)
// Front to back ("under") with 3DGS's early termination, fed fragments near to far: a fragment that would
// take the transmittance below EARLY_STOP is not blended, nor any after it (the resolves' EARLY_STOP forms).
vec3 ftbColour;
float ftbT;
bool ftbDone;
void ftb_begin() {
  ftbColour = vec3(0.0);
  ftbT = 1.0;
  ftbDone = false;
}
void ftb_add(FRAG_T frag) {
  vec4 k = frag_colour(frag);
  float next = ftbT * (1.0 - k.a);
  if (ftbDone || next < EARLY_STOP) {
    ftbDone = true;
    return;
  }
  ftbColour += ftbT * k.a * k.rgb;
  ftbT = next;
}
vec3 ftb_end() { return ftbColour + ftbT * backdrop; }
#endif

// The binding of the sort library's element API (shaders/sorts/api.glsl): fragments far to near.
// An element belongs after another when the other is farther; equal depths are ordered by colour
// (FRAG_FARTHER), so the result never depends on the order the fragments were stored in. The
// array, its size and the loop bound are each variant's (rbs.glsl binds RS to its registers).
// The shader library expands each include once, at its first #include, whatever the #if around
// it: the API comes first, unconditionally.
#include "../sorts/api.glsl"
#define SORT_T FRAG_T
#define SORT_GT(a, b) FRAG_FARTHER(b, a)
// SORT_PACKED_KEY64 (the register networks, rgba8 fragments, a driver with int64; the entry points
// enable GL_ARB_gpu_shader_int64): uvec2(colour, depth bits) read as one 64-bit key, depth high and
// colour low, orders exactly as FRAG_FARTHER does, so far-to-near is max first.
#if defined(SORT_PACKED_KEY64) && !defined(FRAG_COLOUR_RGBA16F) && !defined(FRAG_COLOUR_RGBA32F)
#define SORT_FIRST(a, b) unpackUint2x32(max(packUint2x32(a), packUint2x32(b)))
#define SORT_LAST(a, b) unpackUint2x32(min(packUint2x32(a), packUint2x32(b)))
#endif

#if defined(SORT_RBS) || defined(SORT_RBS_G)
#include "rbs.glsl"
#elif defined(SORT_IS) || defined(SORT_IMS)
FRAG_T frags[MAX_FRAGS];
int frag_count;  // the pixel's fragments: a run-time loop bound, so the sorts work in local memory
#define SORT_N MAX_FRAGS
#define SORT_SIZE frag_count
#define SORT_AT(i) frags[i]
#include "../sorts/insertion.glsl"
#if defined(SORT_IMS) && !defined(SORT_MERGE_HALF_SCRATCH)
#error "IMS merges in Knowles 2013's form: inject SORT_MERGE_HALF_SCRATCH (micro/oit/resolve/resolve_sort.cpp)"
#endif
#if defined(SORT_IMS) && MAX_FRAGS > 32
#include "../sorts/merge.glsl"
#endif
#if defined(EARLY_STOP)
// frags[0, n) far to near, composited from the near end; the backdrop shows through what is left.
vec3 composite_front_to_back(int n) {
  ftb_begin();
  for (int i = n - 1; i >= 0 && !ftbDone; --i) ftb_add(frags[i]);
  return ftb_end();
}
#endif
vec3 resolve_pixel(uint node) {
  int n = 0;
#if defined(SORT_ORDER_CHECK)
  // The list's order, checked while loading in O(n): `ordered` while no pair is out of far-to-near
  // order, `reversed` while no pair is out of near-to-far order.
  // The previous fragment stays in a register: reading frags[n - 1] back from the local array is a
  // gather per fragment where the JIT vectorises over pixels (llvmpipe with AVX-512: docs/drivers.md).
  bool ordered = true, reversed = true;
  FRAG_T prev;
#endif
  while (FRAG_VALID(node) && n < MAX_FRAGS) {  // deeper pixels are truncated (counted on the host)
    FRAG_T f = FRAG_LOAD(node);
    frags[n] = f;
#if defined(SORT_ORDER_CHECK)
    if (n > 0) {
      ordered = ordered && !SORT_GT(prev, f);
      reversed = reversed && !SORT_GT(f, prev);
    }
    prev = f;
#endif
    ++n;
    node = FRAG_NEXT(node);
  }
  frag_count = n;
#if defined(SORT_ORDER_CHECK)
  if (reversed && !ordered) {
    // Near-to-far: reversed in place it is far-to-near (equal neighbours are equal bits).
    for (int i = 0, j = n - 1; i < j; ++i, --j) SORT_SWAP(i, j);
  } else if (!ordered)
#endif
#if defined(SORT_IMS) && MAX_FRAGS > 32
  if (n > 32) sort_merge();
  else
#endif
  sort_insertion();
#if defined(EARLY_STOP)
  return composite_front_to_back(n);
#else
  vec3 c = backdrop;
  for (int i = 0; i < n; ++i) c = blend_over(c, frags[i]);
  return c;
#endif
}
#else
#error "define SORT_IS, SORT_IMS, SORT_RBS or SORT_RBS_G"
#endif
