// HT, hybrid transparency's core (Maule et al. 2013): a k-buffer of the n nearest fragments whole
// (RGBA8 colour, depth), in (depth, colour) order; a fragment pushed out goes to the tail, which
// approx/ht_tail.frag accumulates in a second pass.
// Written against insert/api.glsl (included by approx/insert.frag under its TECH_ define).
// Sorted insertion: the new fragment takes the first slot it precedes and pushes the rest back;
// the last node falls out of the core (into the tail, which is found again in the tail pass).
void insert(ivec2 p, vec4 c, vec4 ct, float z) {
  uint key = packUnorm4x8(c);  // the node keeps the colour whole
  for (int i = 0; i < N; ++i) {
    uvec2 node = STORAGE_LOAD(p, i);
    float nz = node_depth(node);
    if (z < nz || (z == nz && key < node.x)) {
      STORAGE_STORE(p, i, uvec2(key, encode_depth(z)));
      if (nz == DEPTH_EMPTY) break;
      key = node.x;
      z = nz;
    }
  }
}
