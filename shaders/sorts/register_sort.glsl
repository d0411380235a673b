// RS, the register sort of Knowles 2014's register-based block sort (RBS), Listing 5: insertion
// sort unrolled by hand into an insertion network with explicit branching. Every index is a
// literal, so the array needs no dynamic indexing and may stay in registers: there is no
// local-memory form. Outer conditionals (`n > j`) shrink the network to the n elements present at
// run time (n <= SORT_N, the network's size); inner conditionals stop an insertion once the element
// is in place (the early exit). RBS sorts blocks of up to 32 with RS and k-way merges the blocks;
// for up to 32 elements there is one block and RBS is RS.
//   the sort experiment (`rbs`):  n = its `count` uniform, on its SORT_N elements
//   the oit resolves (RBS-L, RBS-G: shaders/resolve/rbs.glsl):  n = the block's fragments, on the
//                                 resolve's `registers` block (SORT_N = RBS_M)
//
// RBS_INSERT_j moves element j down until it is in place: a nest of j compare-and-swaps.
#include "api.glsl"

#if SORT_N > 32
#error "RS sorts one block of at most 32 elements"
#endif

#define RBS_INSERT_1 if (SORT_GREATER(0, 1)) SORT_SWAP(0, 1)
#define RBS_INSERT_2 if (SORT_GREATER(1, 2)) { SORT_SWAP(1, 2) RBS_INSERT_1 }
#define RBS_INSERT_3 if (SORT_GREATER(2, 3)) { SORT_SWAP(2, 3) RBS_INSERT_2 }
#define RBS_INSERT_4 if (SORT_GREATER(3, 4)) { SORT_SWAP(3, 4) RBS_INSERT_3 }
#define RBS_INSERT_5 if (SORT_GREATER(4, 5)) { SORT_SWAP(4, 5) RBS_INSERT_4 }
#define RBS_INSERT_6 if (SORT_GREATER(5, 6)) { SORT_SWAP(5, 6) RBS_INSERT_5 }
#define RBS_INSERT_7 if (SORT_GREATER(6, 7)) { SORT_SWAP(6, 7) RBS_INSERT_6 }
#define RBS_INSERT_8 if (SORT_GREATER(7, 8)) { SORT_SWAP(7, 8) RBS_INSERT_7 }
#define RBS_INSERT_9 if (SORT_GREATER(8, 9)) { SORT_SWAP(8, 9) RBS_INSERT_8 }
#define RBS_INSERT_10 if (SORT_GREATER(9, 10)) { SORT_SWAP(9, 10) RBS_INSERT_9 }
#define RBS_INSERT_11 if (SORT_GREATER(10, 11)) { SORT_SWAP(10, 11) RBS_INSERT_10 }
#define RBS_INSERT_12 if (SORT_GREATER(11, 12)) { SORT_SWAP(11, 12) RBS_INSERT_11 }
#define RBS_INSERT_13 if (SORT_GREATER(12, 13)) { SORT_SWAP(12, 13) RBS_INSERT_12 }
#define RBS_INSERT_14 if (SORT_GREATER(13, 14)) { SORT_SWAP(13, 14) RBS_INSERT_13 }
#define RBS_INSERT_15 if (SORT_GREATER(14, 15)) { SORT_SWAP(14, 15) RBS_INSERT_14 }
#define RBS_INSERT_16 if (SORT_GREATER(15, 16)) { SORT_SWAP(15, 16) RBS_INSERT_15 }
#define RBS_INSERT_17 if (SORT_GREATER(16, 17)) { SORT_SWAP(16, 17) RBS_INSERT_16 }
#define RBS_INSERT_18 if (SORT_GREATER(17, 18)) { SORT_SWAP(17, 18) RBS_INSERT_17 }
#define RBS_INSERT_19 if (SORT_GREATER(18, 19)) { SORT_SWAP(18, 19) RBS_INSERT_18 }
#define RBS_INSERT_20 if (SORT_GREATER(19, 20)) { SORT_SWAP(19, 20) RBS_INSERT_19 }
#define RBS_INSERT_21 if (SORT_GREATER(20, 21)) { SORT_SWAP(20, 21) RBS_INSERT_20 }
#define RBS_INSERT_22 if (SORT_GREATER(21, 22)) { SORT_SWAP(21, 22) RBS_INSERT_21 }
#define RBS_INSERT_23 if (SORT_GREATER(22, 23)) { SORT_SWAP(22, 23) RBS_INSERT_22 }
#define RBS_INSERT_24 if (SORT_GREATER(23, 24)) { SORT_SWAP(23, 24) RBS_INSERT_23 }
#define RBS_INSERT_25 if (SORT_GREATER(24, 25)) { SORT_SWAP(24, 25) RBS_INSERT_24 }
#define RBS_INSERT_26 if (SORT_GREATER(25, 26)) { SORT_SWAP(25, 26) RBS_INSERT_25 }
#define RBS_INSERT_27 if (SORT_GREATER(26, 27)) { SORT_SWAP(26, 27) RBS_INSERT_26 }
#define RBS_INSERT_28 if (SORT_GREATER(27, 28)) { SORT_SWAP(27, 28) RBS_INSERT_27 }
#define RBS_INSERT_29 if (SORT_GREATER(28, 29)) { SORT_SWAP(28, 29) RBS_INSERT_28 }
#define RBS_INSERT_30 if (SORT_GREATER(29, 30)) { SORT_SWAP(29, 30) RBS_INSERT_29 }
#define RBS_INSERT_31 if (SORT_GREATER(30, 31)) { SORT_SWAP(30, 31) RBS_INSERT_30 }

void sort_register(int n) {
#if SORT_N > 1
  if (n > 1) { RBS_INSERT_1 }
#endif
#if SORT_N > 2
  if (n > 2) { RBS_INSERT_2 }
#endif
#if SORT_N > 3
  if (n > 3) { RBS_INSERT_3 }
#endif
#if SORT_N > 4
  if (n > 4) { RBS_INSERT_4 }
#endif
#if SORT_N > 5
  if (n > 5) { RBS_INSERT_5 }
#endif
#if SORT_N > 6
  if (n > 6) { RBS_INSERT_6 }
#endif
#if SORT_N > 7
  if (n > 7) { RBS_INSERT_7 }
#endif
#if SORT_N > 8
  if (n > 8) { RBS_INSERT_8 }
#endif
#if SORT_N > 9
  if (n > 9) { RBS_INSERT_9 }
#endif
#if SORT_N > 10
  if (n > 10) { RBS_INSERT_10 }
#endif
#if SORT_N > 11
  if (n > 11) { RBS_INSERT_11 }
#endif
#if SORT_N > 12
  if (n > 12) { RBS_INSERT_12 }
#endif
#if SORT_N > 13
  if (n > 13) { RBS_INSERT_13 }
#endif
#if SORT_N > 14
  if (n > 14) { RBS_INSERT_14 }
#endif
#if SORT_N > 15
  if (n > 15) { RBS_INSERT_15 }
#endif
#if SORT_N > 16
  if (n > 16) { RBS_INSERT_16 }
#endif
#if SORT_N > 17
  if (n > 17) { RBS_INSERT_17 }
#endif
#if SORT_N > 18
  if (n > 18) { RBS_INSERT_18 }
#endif
#if SORT_N > 19
  if (n > 19) { RBS_INSERT_19 }
#endif
#if SORT_N > 20
  if (n > 20) { RBS_INSERT_20 }
#endif
#if SORT_N > 21
  if (n > 21) { RBS_INSERT_21 }
#endif
#if SORT_N > 22
  if (n > 22) { RBS_INSERT_22 }
#endif
#if SORT_N > 23
  if (n > 23) { RBS_INSERT_23 }
#endif
#if SORT_N > 24
  if (n > 24) { RBS_INSERT_24 }
#endif
#if SORT_N > 25
  if (n > 25) { RBS_INSERT_25 }
#endif
#if SORT_N > 26
  if (n > 26) { RBS_INSERT_26 }
#endif
#if SORT_N > 27
  if (n > 27) { RBS_INSERT_27 }
#endif
#if SORT_N > 28
  if (n > 28) { RBS_INSERT_28 }
#endif
#if SORT_N > 29
  if (n > 29) { RBS_INSERT_29 }
#endif
#if SORT_N > 30
  if (n > 30) { RBS_INSERT_30 }
#endif
#if SORT_N > 31
  if (n > 31) { RBS_INSERT_31 }
#endif
}
