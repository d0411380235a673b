// LAAT, section 6.2: UAT's relative nodes linked into a list (a link per node, a head slot),
// walked instead of sorted; only the changed nodes are written back.
// Written against insert/api.glsl (included by approx/insert.frag under its TECH_ define).
float fT[N + 1];
float fZ[N + 1];

#define LAAT_N (STORAGE_NODES - 1)
#define LAAT_HEAD LAAT_N
uvec2 old[LAAT_N];
int walk[LAAT_N];      // slots in list order, as walked
int seq[LAAT_N + 1];   // slots near to far; slot LAAT_N stands for the new fragment
uvec2 laat_node(float t, float z, int next) {
  return uvec2(((floatBitsToUint(t) ^ ONE_BITS) & ~31u) | uint(next + 1), encode_depth(z));
}
void insert(ivec2 p, vec4 c, vec4 ct, float z) {
  uint head = STORAGE_LOAD(p, LAAT_HEAD).x;
  int cnt = 0, k = 0;
  int slot = int(head) - 1;
  for (int i = 0; i < LAAT_N && slot >= 0; ++i) {  // walk the list: random reads
    uvec2 node = STORAGE_LOAD(p, slot);
    old[slot] = node;
    fT[slot] = at_transmittance(node);
    fZ[slot] = node_depth(node);
    if (fZ[slot] <= z) k = cnt + 1;
    walk[cnt++] = slot;
    slot = int(node.x & 31u) - 1;
  }
  fT[LAAT_N] = ct.a;
  fZ[LAAT_N] = z;
  // Built into a second array: shifting `seq` in place (descending loop here, ascending after the
  // compression) gave wrong lists on llvmpipe, which the CPU model caught; the cause is not isolated.
  for (int i = 0; i <= cnt; ++i) seq[i] = i < k ? walk[i] : (i == k ? LAAT_N : walk[i - 1]);
  int len = cnt + 1;
  int newSlot = cnt;  // not full: the next free slot
  if (cnt == LAAT_N) {
    float before = fT[seq[0]];
    int r = 1;
    float best = DEPTH_EMPTY;
    for (int i = 1; i <= LAAT_N; ++i) {
      float after = before * fT[seq[i]];
      float e = (fZ[seq[i]] - fZ[seq[i - 1]]) * (before - after);
      if (e < best) { best = e; r = i; }
      before = after;
    }
    int compress = seq[r - 1], removed = seq[r];
    float t = fT[compress] * fT[removed];
    fT[compress] = t;
    newSlot = removed;  // the new fragment takes the removed node's slot (unless it was removed)
    len = LAAT_N;
    for (int i = 0; i < LAAT_N; ++i) walk[i] = i < r ? seq[i] : seq[i + 1];
  } else {
    for (int i = 0; i < len; ++i) walk[i] = seq[i];
  }
  // Write back what changed: the links around the new node, the compressed node, the head.
  for (int i = 0; i < len; ++i) {
    int s = walk[i];
    int next = i + 1 < len ? (walk[i + 1] == LAAT_N ? newSlot : walk[i + 1]) : -1;
    int at = s == LAAT_N ? newSlot : s;
    uvec2 node = laat_node(fT[s], fZ[s], next);
    if (s == LAAT_N || node != old[s]) STORAGE_STORE(p, at, node);
  }
  uint first = uint((walk[0] == LAAT_N ? newSlot : walk[0]) + 1);
  if (first != head) STORAGE_STORE(p, LAAT_HEAD, uvec2(first, 0u));
}
