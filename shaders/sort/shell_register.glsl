// Register shell sort, Brüll 2018 Listing 4.14: the swap form of insertion v2 with the gaps of
// Listing 4.13, so every index is a constant once the loops are unrolled.
#include "frags.glsl"
#include "shell_gaps.glsl"

#define SORT_ALGORITHM sort_shell_register

void sort_shell_register() {
  for (int gap_idx = shell_start_gap(SORT_SIZE); gap_idx < 4; ++gap_idx) {
    int gap = shell_gaps[gap_idx];
    for (int i = gap; i < SORT_SIZE; ++i)
      for (int j = i; j >= gap && SORT_GREATER(j - gap, j); j -= gap) SORT_SWAP(j - gap, j);
  }
}
