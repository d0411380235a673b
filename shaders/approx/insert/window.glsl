// WINDOW-SORT, a StopThePop-style windowed per-pixel sort (Radl et al. 2024, its k-buffer mode): the
// splats arrive in the global order (their centres' depths, near to far: GLOBAL-SORT's key pass and radix
// sort), each pixel keeps the WINDOW_N nearest pending fragments sorted by their own depth key, and once
// the window is full each new fragment makes the nearest of the window and itself leave: it is blended
// front to back (window.glsl). The resolve flushes the window in order. Exact when no fragment arrives
// more than WINDOW_N places out of its per-pixel order.
// Written against insert/api.glsl (included by approx/insert.frag under its TECH_ define).
#include "kbuffer.glsl"
#include "../window.glsl"
void insert(ivec2 p, vec4 c, vec4 ct, float z) {
  uint key = packUnorm4x8(c);
  if (STORAGE_LOAD(p, WINDOW_N - 1).y == 0u) {  // room left: the window takes it
    kbuffer_insert(p, key, z, WINDOW_N);
    return;
  }
  // Full: walked from the back, every node that precedes the carried fragment takes its place and is
  // carried on; what is carried out of slot 0 is the nearest of the window and the new fragment.
  for (int i = WINDOW_N - 1; i >= 0; --i) {
    uvec2 node = STORAGE_LOAD(p, i);
    float nz = node_depth(node);
    if (kbuffer_precedes(nz, node.x, z, key)) {
      STORAGE_STORE(p, i, uvec2(key, encode_depth(z)));
      key = node.x;
      z = nz;
    }
  }
#ifdef OITBENCH_FAULT_WRONG_RESULT
  key = packUnorm4x8(c);  // the new fragment blended at once, whatever the window held: the model must notice
#endif
  window_blend(p, key);
}
