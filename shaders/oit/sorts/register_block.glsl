// Register-based block sort, RBS-L (Knowles 2014, listings 3-6). Fragments are read straight from
// the list into blocks of RBS_M registers, each block is sorted in registers (RS: an insertion
// network whose inner loops have constant bounds, so the compiler unrolls them and every index is
// a constant), written to local memory, and the MAX_K blocks are k-way merged, blending during the
// merge. A pixel that fits one block (MAX_K == 1) never touches local memory.
// Expects: RBS_M, MAX_K (MAX_FRAGS = RBS_M * MAX_K), blend_over(vec3, uvec2), background.
#pragma optionNV(unroll all)
uvec2 registers[RBS_M];

// RS (listing 4): insertion as swaps. The inner loop has constant bounds, so the compiler unrolls
// it and every index into `registers` is a constant; the `i <= j` guard shrinks the network to the
// pixel's count and `moving` stops an insertion once its element is in place.
void register_sort(int m) {
  for (int j = 1; j < m; ++j) {
    bool moving = true;
    for (int i = RBS_M - 1; i > 0; --i) {
      if (i <= j && moving) {
        if (registers[i - 1].y < registers[i].y) {
          uvec2 t = registers[i - 1];
          registers[i - 1] = registers[i];
          registers[i] = t;
        } else {
          moving = false;
        }
      }
    }
  }
}

// Reads up to RBS_M fragments of the list from `node` into registers; returns how many.
int load_block(inout uint node) {
  int m = 0;
  for (int i = 0; i < RBS_M; ++i) {
    if (FRAG_VALID(node)) {
      registers[i] = FRAG_LOAD(node);
      node = FRAG_NEXT(node);
      m = i + 1;
    }
  }
  return m;
}

#if MAX_K == 1
vec3 resolve_pixel(uint node) {
  int m = load_block(node);
  register_sort(m);
  vec3 c = background;
  for (int i = 0; i < RBS_M; ++i)
    if (i < m) c = blend_over(c, registers[i]);
  return c;
}
#else
uvec2 frags[MAX_FRAGS];  // the sorted blocks (local memory)

vec3 resolve_pixel(uint node) {
  int n = 0, k = 0;
  while (FRAG_VALID(node) && k < MAX_K) {
    int m = load_block(node);
    register_sort(m);
    for (int i = 0; i < RBS_M; ++i)
      if (i < m) frags[k * RBS_M + i] = registers[i];
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
    uint best = 0u;
    for (int j = 0; j < MAX_K; ++j)
      if (blockIdx[j] < blockEnd[j] && (b < 0 || candidate[j].y > best)) {
        b = j;
        best = candidate[j].y;
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
