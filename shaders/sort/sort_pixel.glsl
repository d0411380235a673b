// process_pixel(p), one pixel's work, shared by the fragment and compute entry points: load its
// SORT_N fragments, sort them with the library sort chosen by SORT_USE_<FILE> (algorithms.glsl),
// write them back.
#include "../common/oitbench.glsl"
#include "frags.glsl"
#include "algorithms.glsl"

#ifndef SORT_ALGORITHM
#error "define one SORT_USE_<FILE> of algorithms.glsl"
#endif

void process_pixel(ivec2 p) {
  frags_load(p);
  SORT_ALGORITHM();
#ifdef OITBENCH_FAULT_WRONG_RESULT
  // The validator must see both kinds of error: a changed payload and an out-of-order pair.
  if (p == ivec2(1, 1)) SORT_AT(SORT_N - 1).y ^= 1u;
  if (p == ivec2(2, 1)) SORT_SWAP(0, SORT_N - 1);
#endif
  frags_store(p);
}
