// WINDOW-SORT's per-pixel state (a StopThePop-style windowed sort, Radl et al. 2024): slots 0..WINDOW_N-1
// the window, a k-buffer of the pending fragments (insert/kbuffer.glsl's nodes, nearest first), and two
// slots after it the colour blended so far front to back: (r, g) as float bits, then (b, transmittance)
// with the transmittance in the AT encoding of nodes.glsl, so that cleared storage reads (0, 0, 0; T 1).
// Mirrored on the CPU by micro/oit/approx/window_model.cpp.
#ifndef APPROX_WINDOW_GLSL
#define APPROX_WINDOW_GLSL
#include "nodes.glsl"

#define WINDOW_N (STORAGE_NODES - 2)

void window_load_blended(ivec2 p, out vec3 c, out float t) {
  uvec2 rg = STORAGE_LOAD(p, WINDOW_N), bt = STORAGE_LOAD(p, WINDOW_N + 1);
  c = vec3(uintBitsToFloat(rg.x), uintBitsToFloat(rg.y), uintBitsToFloat(bt.x));
  t = uintBitsToFloat(bt.y ^ ONE_BITS);
}

// One fragment (packed RGBA8) blended behind what the pixel holds: C += T a c, T *= 1 - a.
void window_blend(ivec2 p, uint key) {
  vec3 c;
  float t;
  window_load_blended(p, c, t);
  vec4 k = unpackUnorm4x8(key);
  c += t * k.a * k.rgb;
  t *= 1.0 - k.a;
  STORAGE_STORE(p, WINDOW_N, uvec2(floatBitsToUint(c.r), floatBitsToUint(c.g)));
  STORAGE_STORE(p, WINDOW_N + 1, uvec2(floatBitsToUint(c.b), floatBitsToUint(t) ^ ONE_BITS));
}

#endif
