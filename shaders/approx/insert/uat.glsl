// UAT, section 6.1: unsorted relative transmittance, sorted in registers, rect metric.
// Written against insert/api.glsl (included by approx/insert.frag under its TECH_ define).
float fT[N + 1];
float fZ[N + 1];

int order[N + 1];
void insert(ivec2 p, vec4 c, vec4 ct, float z) {
  fT[N] = ct.a;
  fZ[N] = z;
  int empty = -1;
  for (int i = 0; i < N; ++i) {
    uvec2 node = STORAGE_LOAD(p, i);
    fT[i] = at_transmittance(node);
    fZ[i] = node_depth(node);
    if (empty < 0 && fZ[i] == DEPTH_EMPTY) empty = i;
  }
  if (empty >= 0) {
    STORAGE_STORE(p, empty, at_node(fT[N], z));
    return;
  }
  // Sort the node indices by depth (ties: by slot, the new fragment last) in registers.
  for (int i = 0; i <= N; ++i) order[i] = i;
  for (int i = 1; i <= N; ++i)
    for (int j = i; j > 0; --j) {
      int a = order[j - 1], b = order[j];
      if (fZ[a] > fZ[b] || (fZ[a] == fZ[b] && a > b)) { order[j - 1] = b; order[j] = a; }
    }
  // Rect metric on the absolute visibility (prefix products of the relative transmittances).
  float before = fT[order[0]];
  int r = 1;
  float best = DEPTH_EMPTY;
  for (int i = 1; i <= N; ++i) {
    float after = before * fT[order[i]];
    float e = (fZ[order[i]] - fZ[order[i - 1]]) * (before - after);
    if (e < best) { best = e; r = i; }
    before = after;
  }
  int removeIdx = order[r], compressIdx = order[r - 1];
  float t = fT[compressIdx] * fT[removeIdx];
  if (compressIdx == N) {
    STORAGE_STORE(p, removeIdx, at_node(t, fZ[N]));
  } else {
    STORAGE_STORE(p, compressIdx, at_node(t, fZ[compressIdx]));
    if (removeIdx != N) STORAGE_STORE(p, removeIdx, at_node(fT[N], z));
  }
}
