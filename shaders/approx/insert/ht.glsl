// HT, hybrid transparency's core (Maule et al. 2013), and FIRST-K (HTGS's ALPHA_BLEND_FIRST_K, Hahlbohm et
// al. 2025): a k-buffer of the n nearest fragments whole (RGBA8 colour, depth), in (depth, colour) order.
// A fragment pushed out goes to HT's tail, which approx/ht_tail.frag accumulates in a second pass;
// FIRST-K drops it.
// Written against insert/api.glsl (included by approx/insert.frag under its TECH_ define).
#include "kbuffer.glsl"
void insert(ivec2 p, vec4 c, vec4 ct, float z) {
#if defined(HT_HTGS)
  if (c.a < HTGS_CORE_ALPHA) return;  // HTGS: a faint fragment goes to the tail whatever its depth
#endif
  kbuffer_insert(p, packUnorm4x8(c), z, N);
}
