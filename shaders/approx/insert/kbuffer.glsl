// The k-buffer insertion HT's core, FIRST-K and WINDOW-SORT's window share: slots 0..n-1 of the pixel hold
// fragments whole (RGBA8 colour, depth) in (depth, colour) order, empty slots (DEPTH_EMPTY) last.
// kbuffer_precedes: fragment a before fragment b in that order (equal depths by the packed colour, so the
// order is deterministic whatever order the fragments arrive in).
bool kbuffer_precedes(float za, uint ka, float zb, uint kb) { return za < zb || (za == zb && ka < kb); }

// The new fragment takes the first slot it precedes and pushes the rest back; a full buffer's last node
// falls out (HT finds it again in its tail pass; FIRST-K drops it).
void kbuffer_insert(ivec2 p, uint key, float z, int n) {
  for (int i = 0; i < n; ++i) {
    uvec2 node = STORAGE_LOAD(p, i);
    float nz = node_depth(node);
    if (kbuffer_precedes(z, key, nz, node.x)) {
      STORAGE_STORE(p, i, uvec2(key, encode_depth(z)));
      if (nz == DEPTH_EMPTY) break;
      key = node.x;
      z = nz;
    }
  }
}
