// Register-based block sort, RBS-G (Knowles 2014, section 3): like RBS-L, but each block sorted in
// registers is written back in place into the list's own nodes in global memory (the nodes it was
// read from, in list order) instead of a local array, and the k-way merge reads its candidates
// from there. No MAX_FRAGS-sized local array, so nothing here limits occupancy and BMA is not
// needed; the price is a second pass over every node in global memory (write and re-read).
// After the resolve each pixel's list holds sorted runs of RBS_M: the same fragments, so the CPU
// reference (which sorts for itself) still applies.
// Expects: RBS_M, MAX_K (MAX_FRAGS = RBS_M * MAX_K), blend_over(vec3, uvec2), background, and a
// storage layout with FRAG_STORE(node, frag).
#include "register_sort.glsl"

#define RS_WRITE_BACK(i) if ((i) < m) { FRAG_STORE(dst, registers[i]); dst = FRAG_NEXT(dst); }

vec3 resolve_pixel(uint node) {
  uint blockHead[MAX_K];  // each sorted block's next unmerged node in global memory
  int blockLeft[MAX_K];   // and how many of its fragments are not merged yet
  int n = 0, k = 0;
  while (FRAG_VALID(node) && k < MAX_K) {
    uint start = node;
    uint dst = node;
    int m = load_block(node);
    register_sort(m);
    RS_FOR_EACH(RS_WRITE_BACK)
    blockHead[k] = start;
    blockLeft[k] = m;
    n += m;
    ++k;
  }
  // k-way merge (listing 6): the candidate (deepest unmerged fragment) of each block in a register.
  uvec2 candidate[MAX_K];
  for (int j = 0; j < MAX_K; ++j)
    if (j < k) candidate[j] = FRAG_LOAD(blockHead[j]);
  vec3 c = background;
  for (int f = 0; f < n; ++f) {
    int b = -1;
    uvec2 best = uvec2(0u);
    for (int j = 0; j < MAX_K; ++j)
      if (j < k && blockLeft[j] > 0 && (b < 0 || FRAG_FARTHER(candidate[j], best))) {  // ties by colour, as everywhere
        b = j;
        best = candidate[j];
      }
    for (int j = 0; j < MAX_K; ++j)
      if (j == b) {
        c = blend_over(c, candidate[j]);
        if (--blockLeft[j] > 0) {
          blockHead[j] = FRAG_NEXT(blockHead[j]);
          candidate[j] = FRAG_LOAD(blockHead[j]);
        }
      }
  }
  return c;
}
