// Table A.2 of Brüll 2018: a full-screen pass that inserts `repeat` new elements, one after the
// other, into each pixel's sorted array of SORT_N fragments. Each new element overwrites the
// current minimum (frags[0]) and is moved to its place, as a k-buffer that keeps the largest keys.
// The new elements come from a hash of (pixel, round, seed) that micro/experiments/insert.cpp
// reproduces bit for bit:
//   KEYS_RANDOM  key uniform in [0, 1) (exact: a 24-bit integer times 2^-24)
//   KEYS_FRONT   key -1 - round: smaller than everything, stays at frags[0] (early out's best case)
//   KEYS_BACK    key 1 + round: larger than everything, travels to the end (its worst case)
#include "../common/oitbench.glsl"
#include "insert_into_sorted.glsl"

#ifndef INSERT_ALGORITHM
#error "define INSERT_ALGORITHM (insert_early_out, insert_no_early_out or insert_two_moves)"
#endif

uniform int repeat;
uniform uint seed;

layout(location = 0) out uint first_payload;

// A 32-bit integer mixer (the "lowbias32" constants); insert.cpp has the same function.
uint mix32(uint x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

SORT_T new_element(int pixel, int round) {
  uint h = mix32(uint(pixel) ^ mix32(uint(round) + seed * 0x9e3779b9u));
#if defined(KEYS_RANDOM)
  float key = float(h >> 8) * (1.0 / 16777216.0);
#elif defined(KEYS_FRONT)
  float key = -1.0 - float(round);
#elif defined(KEYS_BACK)
  float key = 1.0 + float(round);
#else
#error "define KEYS_RANDOM, KEYS_FRONT or KEYS_BACK"
#endif
  return SORT_T(floatBitsToUint(key), mix32(h));
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  int pixel = frags_pixel_index(p);
  frags_load(p);
  // `repeat` is a uniform: this loop stays a loop, only the insertion inside may unroll.
  for (int round = 0; round < repeat; ++round) {
    SORT_T e = new_element(pixel, round);
    SORT_AT(0) = e;
    INSERT_ALGORITHM(e);
  }
#ifdef OITBENCH_FAULT_WRONG_RESULT
  if (p == ivec2(1, 1)) SORT_AT(SORT_N - 1).y ^= 1u;  // one payload off: the validator must notice
#endif
  frags_store(p);
  first_payload = SORT_AT(0).y + uint(oitbench_fault_hang(zero));
}
