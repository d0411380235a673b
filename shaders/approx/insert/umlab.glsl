// UMLAB, Listings 5.1 + 5.2: unsorted, merge the two farthest, store at most two nodes.
// Written against insert/api.glsl (included by approx/insert.frag under its TECH_ define).
vec4 fC[N + 1];  // (C, T)
float fZ[N + 1];
vec4 merge(vec4 a, vec4 b) { return vec4(a.rgb + a.a * b.rgb, a.a * b.a); }

void insert(ivec2 p, vec4 c, vec4 ct, float z) {
  fC[N] = ct;
  fZ[N] = z;
  for (int i = 0; i < N; ++i) {
    uvec2 node = STORAGE_LOAD(p, i);
    fC[i] = mlab_value(node);
    fZ[i] = node_depth(node);
  }
  int maxIdx = 0;
  float maxZ = -1.0;
  for (int i = 0; i <= N; ++i)
    if (fZ[i] > maxZ) { maxZ = fZ[i]; maxIdx = i; }
  if (maxZ == DEPTH_EMPTY) {  // Listing 5.2: an initialisation node is left, no merge
    STORAGE_STORE(p, maxIdx, mlab_node(ct, z));
    return;
  }
  int smaxIdx = 0;
  float smaxZ = -1.0;
  for (int i = 0; i <= N; ++i)
    if (fZ[i] > smaxZ && i != maxIdx) { smaxZ = fZ[i]; smaxIdx = i; }
  vec4 merged = merge(fC[smaxIdx], fC[maxIdx]);
  if (maxIdx == N) {
    maxIdx = smaxIdx;
    smaxIdx = N;
  }
  STORAGE_STORE(p, maxIdx, mlab_node(merged, smaxZ));
  if (smaxIdx != N) STORAGE_STORE(p, smaxIdx, mlab_node(ct, z));
}
