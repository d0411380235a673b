// Register-based block sort, RBS-L (Knowles 2014, listings 3-6). Fragments are read straight from
// the list into blocks of RBS_M registers, each block is sorted in registers (RS, in
// register_sort.glsl), written to local memory, and the MAX_K blocks are k-way merged, blending
// during the merge. A pixel that fits one block (MAX_K == 1) never touches local memory.
// Expects: RBS_M, MAX_K (MAX_FRAGS = RBS_M * MAX_K), blend_over(vec3, uvec2), background.
#include "register_sort.glsl"

#if MAX_K == 1
vec3 resolve_pixel(uint node) {
  int m = load_block(node);
  register_sort(m);
  vec3 c = background;
#define RS_BLEND(i) if ((i) < m) c = blend_over(c, registers[i]);
  RS_FOR_EACH(RS_BLEND)
  return c;
}
#else
uvec2 frags[MAX_FRAGS];  // the sorted blocks (local memory)

vec3 resolve_pixel(uint node) {
  int n = 0, k = 0;
  while (FRAG_VALID(node) && k < MAX_K) {
    int m = load_block(node);
    register_sort(m);
#define RS_STORE(i) if ((i) < m) frags[k * RBS_M + (i)] = registers[i];
    RS_FOR_EACH(RS_STORE)
    n += m;
    ++k;
  }
  // k-way merge: the candidate (deepest remaining fragment) of each block stays in a register.
  uvec2 candidate[MAX_K];
  int blockIdx[MAX_K], blockEnd[MAX_K];
  for (int j = 0; j < MAX_K; ++j) {
    blockIdx[j] = j * RBS_M;
    blockEnd[j] = j < k ? min((j + 1) * RBS_M, n) : blockIdx[j];
    if (j < k) candidate[j] = frags[blockIdx[j]];
  }
  vec3 c = background;
  for (int f = 0; f < n; ++f) {
    int b = -1;
    uvec2 best = uvec2(0u);
    for (int j = 0; j < MAX_K; ++j)
      if (blockIdx[j] < blockEnd[j] && (b < 0 || FRAG_FARTHER(candidate[j], best))) {  // ties by colour, as everywhere
        b = j;
        best = candidate[j];
      }
    for (int j = 0; j < MAX_K; ++j)
      if (j == b) {
        c = blend_over(c, candidate[j]);
        ++blockIdx[j];
        if (blockIdx[j] < blockEnd[j]) candidate[j] = frags[blockIdx[j]];
      }
  }
  return c;
}
#endif
