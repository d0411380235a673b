// MLAB, Listing 3.1: one bubble pass, merge the last two nodes, store all n.
// Written against insert/api.glsl (included by approx/insert.frag under its TECH_ define).
vec4 fC[N + 1];  // (C, T)
float fZ[N + 1];
vec4 merge(vec4 a, vec4 b) { return vec4(a.rgb + a.a * b.rgb, a.a * b.a); }

void insert(ivec2 p, vec4 c, vec4 ct, float z) {
  fC[0] = ct;
  fZ[0] = z;
  for (int i = 0; i < N; ++i) {
    uvec2 node = STORAGE_LOAD(p, i);
    fC[i + 1] = mlab_value(node);
    fZ[i + 1] = node_depth(node);
  }
  for (int i = 0; i < N; ++i) {
    if (fZ[i] > fZ[i + 1]) {
      vec4 tc = fC[i]; fC[i] = fC[i + 1]; fC[i + 1] = tc;
      float tz = fZ[i]; fZ[i] = fZ[i + 1]; fZ[i + 1] = tz;
    }
  }
  fC[N - 1] = merge(fC[N - 1], fC[N]);
  for (int i = 0; i < N; ++i) STORAGE_STORE(p, i, mlab_node(fC[i], fZ[i]));
}
