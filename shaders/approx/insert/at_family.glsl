// The AT family's sorted insertion (Brüll 2018, section 3.6): absolute transmittance nodes, the new
// fragment inserted after the nodes at the same or smaller depth, then one node removed (never the
// first) where `at_error` (defined by at.glsl or hat.glsl after this) is least, underestimating:
// its predecessor takes its transmittance.
float at_error(float tPrev, float t, float zPrev, float z);
float fT[N + 1];
float fZ[N + 1];

void insert(ivec2 p, vec4 c, vec4 ct, float z) {
  float a = ct.a;  // the fragment's transmittance
  int k = 0;             // insertion position: after the nodes at the same or smaller depth
  for (int i = 0; i < N; ++i) {
    uvec2 node = STORAGE_LOAD(p, i);
    fT[i] = at_transmittance(node);
    fZ[i] = node_depth(node);
    if (fZ[i] <= z) k = i + 1;
  }
  for (int i = N; i > k; --i) {
    fT[i] = fT[i - 1] * a;
    fZ[i] = fZ[i - 1];
  }
  fT[k] = (k > 0 ? fT[k - 1] : 1.0) * a;
  fZ[k] = z;
  if (fZ[N] != DEPTH_EMPTY) {
    // Compress: remove the node r (never the first) with the least error, underestimating:
    // its predecessor takes its transmittance.
    int r = 1;
    float best = DEPTH_EMPTY;
    for (int i = 1; i <= N; ++i) {
      float e = at_error(fT[i - 1], fT[i], fZ[i - 1], fZ[i]);
      if (e < best) { best = e; r = i; }
    }
    fT[r - 1] = fT[r];
    for (int i = r; i < N; ++i) {
      fT[i] = fT[i + 1];
      fZ[i] = fZ[i + 1];
    }
  }
  for (int i = 0; i < N; ++i) STORAGE_STORE(p, i, at_node(fT[i], fZ[i]));
}
