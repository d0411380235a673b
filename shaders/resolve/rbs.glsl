// The register-based block sort of the oit resolves, RBS-L and RBS-G (Knowles 2014, listings 3-6),
// composed from the library's RS network (shaders/sorts/register_sort.glsl, the same file the sort
// experiment's `rbs` times) or a register network (shaders/sorts/network.glsl, the sort
// experiment's bitonic-network and odd-even-merge-network) and this resolve's own parts, which stay here because they are
// written against the fragment storage API and blend while they merge, not against the sort
// library's element API: load_block() reads up to RBS_M fragments of the list into `registers`,
// the network sorts them there (this file binds the library's SORT_AT to `registers`), and the
// k-way merge of listing 6 blends the blocks far to near.
//   SORT_RBS    RBS-L: each sorted block is written to a local array of MAX_FRAGS and the MAX_K
//               blocks are merged from there. A pixel that fits one block (MAX_K == 1) never
//               touches local memory.
//   SORT_RBS_G  RBS-G (Knowles 2014, section 3): each sorted block is written back in place into
//               the list's own nodes in global memory (the nodes it was read from, in list order)
//               and the merge reads its candidates from there. No MAX_FRAGS-sized local array, so
//               nothing here limits occupancy and BMA is not needed; the price is a second pass
//               over every node in global memory (write and re-read). After the resolve each
//               pixel's list holds sorted runs of RBS_M: the same fragments, so the CPU reference
//               (which sorts for itself) still applies.
// Expects (resolve_pixel.glsl): sorts/api.glsl and SORT_T / SORT_GT bound, RBS_M (<= 32), MAX_K
// (MAX_FRAGS = RBS_M * MAX_K), blend_over(vec3, FRAG_T), backdrop, the storage API (RBS-G: with
// FRAG_STORE); with EARLY_STOP (RBS-L only) resolve_pixel.glsl's ftb_* front-to-back composite.
#pragma optionNV(unroll all)

// The binding of the library's API for the block sort: the block in registers, every index a constant.
FRAG_T registers[RBS_M];
#define SORT_N RBS_M
#define SORT_SIZE RBS_M
#define SORT_AT(i) registers[i]
#include "../sorts/unroll.glsl"

#if !defined(SORT_EACH_INDEX)
#error "RBS_M must be at most 32"
#endif

// The block sort (the block_sort parameter, micro/oit/resolve/resolve_sort.hpp):
//   (default)                    RS (register_sort.glsl), shrunk to the block's m fragments
//   SORT_NETWORK_BITONIC,        a branchless register network (network.glsl) of RBS_M elements;
//   SORT_NETWORK_ODD_EVEN_MERGE  a block of m < RBS_M is padded with FRAG_ZERO (depth 0, colour 0:
//                                the nearest possible fragment, so it sorts after every real one;
//                                a real fragment equal to it is the same bits, so which of the two
//                                lands in the first m slots changes nothing)
#if defined(SORT_NETWORK_BITONIC) || defined(SORT_NETWORK_ODD_EVEN_MERGE)
#define RBS_NETWORK
#include "../sorts/network.glsl"
#define RBS_SORT_BLOCK(m) sort_network()
#define RBS_PAD(i) else registers[i] = FRAG_ZERO;
#else
#include "../sorts/register_sort.glsl"
#define RBS_SORT_BLOCK(m) sort_register(m)
#define RBS_PAD(i)
#endif

// SORT_ORDER_CHECK (RBS-L, the order_check parameter): the list's order is checked while its blocks
// load, as resolve_pixel.glsl does for IS: a list already far-to-near is blended as it is, one
// near-to-far backwards, with no sort and no merge; a block is sorted only once the list has shown
// itself neither (a mixed list turns so within its first block, so the check costs it little).
#if defined(SORT_ORDER_CHECK) && defined(SORT_RBS)
bool rbsOrdered, rbsReversed, rbsHasPrev;  // this pixel's list so far: far-to-near, near-to-far
FRAG_T rbsPrev;                            // its last fragment, kept in a register
void rbs_check_begin() {
  rbsOrdered = true;
  rbsReversed = true;
  rbsHasPrev = false;
}
#define RBS_CHECK(f)                                 \
  if (rbsHasPrev) {                                  \
    rbsOrdered = rbsOrdered && !SORT_GT(rbsPrev, f); \
    rbsReversed = rbsReversed && !SORT_GT(f, rbsPrev); \
  }                                                  \
  rbsPrev = f;                                       \
  rbsHasPrev = true;
#define RBS_MIXED() (!rbsOrdered && !rbsReversed)
#elif defined(SORT_ORDER_CHECK) && defined(SORT_RBS_G)
#error "the order check is RBS-L's (RBS-G writes its sorted blocks back in place)"
#else
#define RBS_CHECK(f)
#endif

// Reads up to RBS_M fragments of the list from `node` into registers (a network's padding after
// them); returns how many.
#define RBS_LOAD(i) if (FRAG_VALID(node)) { registers[i] = FRAG_LOAD(node); RBS_CHECK(registers[i]) node = FRAG_NEXT(node); m = (i) + 1; } RBS_PAD(i)
int load_block(inout uint node) {
  int m = 0;
  SORT_EACH_INDEX(RBS_LOAD)
  return m;
}

#if defined(SORT_RBS) && MAX_K == 1
vec3 resolve_pixel(uint node) {
#if defined(SORT_ORDER_CHECK)
  rbs_check_begin();
#endif
  int m = load_block(node);
#if defined(EARLY_STOP)  // front to back: near to far, stopped early
  ftb_begin();
#if defined(SORT_ORDER_CHECK)
  if (rbsReversed && !rbsOrdered) {  // near-to-far as loaded
#define RBS_ADD(i) if ((i) < m) ftb_add(registers[i]);
    SORT_EACH_INDEX(RBS_ADD)
    return ftb_end();
  }
  if (!rbsOrdered)
#endif
  RBS_SORT_BLOCK(m);
#define RBS_ADD_BACK(i) if (RBS_M - 1 - (i) < m) ftb_add(registers[RBS_M - 1 - (i)]);
  SORT_EACH_INDEX(RBS_ADD_BACK)
  return ftb_end();
#else
  vec3 c = backdrop;
#if defined(SORT_ORDER_CHECK)
  if (rbsReversed && !rbsOrdered) {  // near-to-far: blended from its far end
#define RBS_BLEND_BACK(i) if (RBS_M - 1 - (i) < m) c = blend_over(c, registers[RBS_M - 1 - (i)]);
    SORT_EACH_INDEX(RBS_BLEND_BACK)
    return c;
  }
  if (!rbsOrdered)
#endif
  RBS_SORT_BLOCK(m);
#define RBS_BLEND(i) if ((i) < m) c = blend_over(c, registers[i]);
  SORT_EACH_INDEX(RBS_BLEND)
  return c;
#endif
}
#elif defined(SORT_RBS)
FRAG_T frags[MAX_FRAGS];  // the sorted blocks (local memory)

#if defined(EARLY_STOP)
// The k-way merge front to back: each block (sorted far to near) is read from its near end, the nearest
// of the candidates blended next ("under"), until the transmittance stops it.
vec3 merge_front_to_back(int n, int k) {
  FRAG_T candidate[MAX_K];
  int blockIdx[MAX_K], blockBegin[MAX_K];
  for (int j = 0; j < MAX_K; ++j) {
    blockBegin[j] = j * RBS_M;
    blockIdx[j] = (j < k ? min((j + 1) * RBS_M, n) : blockBegin[j]) - 1;
    if (j < k) candidate[j] = frags[blockIdx[j]];
  }
  ftb_begin();
  for (int f = 0; f < n && !ftbDone; ++f) {
    int b = -1;
    FRAG_T best = FRAG_ZERO;
    for (int j = 0; j < MAX_K; ++j)
      if (blockIdx[j] >= blockBegin[j] && (b < 0 || FRAG_FARTHER(best, candidate[j]))) {
        b = j;
        best = candidate[j];
      }
    for (int j = 0; j < MAX_K; ++j)
      if (j == b) {
        ftb_add(candidate[j]);
        --blockIdx[j];
        if (blockIdx[j] >= blockBegin[j]) candidate[j] = frags[blockIdx[j]];
      }
  }
  return ftb_end();
}
#endif

vec3 resolve_pixel(uint node) {
  int n = 0, k = 0;
#if defined(SORT_ORDER_CHECK)
  rbs_check_begin();
  int unsortedBlocks = 0;  // blocks stored near-to-far while the list still looked reversed
#endif
  while (FRAG_VALID(node) && k < MAX_K) {
    int m = load_block(node);
#if defined(SORT_ORDER_CHECK)
    if (!RBS_MIXED()) {
      if (!rbsOrdered) unsortedBlocks = k + 1;  // stored as loaded: sorted only if the list turns mixed
    } else
#endif
    RBS_SORT_BLOCK(m);
#define RBS_STORE(i) if ((i) < m) frags[k * RBS_M + (i)] = registers[i];
    SORT_EACH_INDEX(RBS_STORE)
    n += m;
    ++k;
  }
#if defined(SORT_ORDER_CHECK) && defined(EARLY_STOP)
  if (rbsOrdered || rbsReversed) {  // far-to-near from its near end, near-to-far from its start
    ftb_begin();
    for (int i = 0; i < n && !ftbDone; ++i) ftb_add(frags[rbsOrdered ? n - 1 - i : i]);
    return ftb_end();
  }
#elif defined(SORT_ORDER_CHECK)
  vec3 c0 = backdrop;
  if (rbsOrdered) {  // far-to-near as it is: no merge
    for (int i = 0; i < n; ++i) c0 = blend_over(c0, frags[i]);
    return c0;
  }
  if (rbsReversed) {  // near-to-far: blended from its far end
    for (int i = n - 1; i >= 0; --i) c0 = blend_over(c0, frags[i]);
    return c0;
  }
#endif
#if defined(SORT_ORDER_CHECK)
  // Mixed after a near-to-far start: the blocks stored unsorted are reversed, which sorts them.
  for (int j = 0; j < unsortedBlocks; ++j)
    for (int i = j * RBS_M, e = min((j + 1) * RBS_M, n) - 1; i < e; ++i, --e) {
      FRAG_T t = frags[i];
      frags[i] = frags[e];
      frags[e] = t;
    }
#endif
#if defined(EARLY_STOP)
  return merge_front_to_back(n, k);
#else
  // k-way merge: the candidate (deepest remaining fragment) of each block stays in a register.
  FRAG_T candidate[MAX_K];
  int blockIdx[MAX_K], blockEnd[MAX_K];
  for (int j = 0; j < MAX_K; ++j) {
    blockIdx[j] = j * RBS_M;
    blockEnd[j] = j < k ? min((j + 1) * RBS_M, n) : blockIdx[j];
    if (j < k) candidate[j] = frags[blockIdx[j]];
  }
  vec3 c = backdrop;
  for (int f = 0; f < n; ++f) {
    int b = -1;
    FRAG_T best = FRAG_ZERO;
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
#endif
}
#elif defined(SORT_RBS_G)
#define RBS_WRITE_BACK(i) if ((i) < m) { FRAG_STORE(dst, registers[i]); dst = FRAG_NEXT(dst); }

vec3 resolve_pixel(uint node) {
  uint blockHead[MAX_K];  // each sorted block's next unmerged node in global memory
  int blockLeft[MAX_K];   // and how many of its fragments are not merged yet
  int n = 0, k = 0;
  while (FRAG_VALID(node) && k < MAX_K) {
    uint start = node;
    uint dst = node;
    int m = load_block(node);
    RBS_SORT_BLOCK(m);
    SORT_EACH_INDEX(RBS_WRITE_BACK)
    blockHead[k] = start;
    blockLeft[k] = m;
    n += m;
    ++k;
  }
  // k-way merge (listing 6): the candidate (deepest unmerged fragment) of each block in a register.
  FRAG_T candidate[MAX_K];
  for (int j = 0; j < MAX_K; ++j)
    if (j < k) candidate[j] = FRAG_LOAD(blockHead[j]);
  vec3 c = backdrop;
  for (int f = 0; f < n; ++f) {
    int b = -1;
    FRAG_T best = FRAG_ZERO;
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
#else
#error "rbs.glsl is for SORT_RBS or SORT_RBS_G"
#endif
