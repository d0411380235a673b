// Standard shell sort, Brüll 2018 Listing 4.13, gaps {20, 9, 4, 1}. The listing's inner loop
// decrements j before the shift (`j -= gap; a[j] = a[j - gap]`), which reads below the array;
// this is the textbook order (shift, then step), which the listing evidently meant.
//
// Mesa 22.3.6 llvmpipe miscompiles this hole-index shape (`a[j] = a[j - gap]` ... `a[j] = key`): the
// shifts are lost, even with gap == 1 and in either memory form, so `shell` is reported invalid
// there. sort_shell_offset is the same algorithm in Listing 4.11's shape (j trails the hole by one
// gap: `a[j + gap] = a[j]` ... `a[j + gap] = key`), which llvmpipe compiles correctly.
#include "frags.glsl"
#include "shell_gaps.glsl"

#if defined(SORT_SHELL_OFFSET)
#define SORT_ALGORITHM sort_shell_offset
#else
#define SORT_ALGORITHM sort_shell
#endif

void sort_shell() {
  for (int gap_idx = shell_start_gap(SORT_SIZE); gap_idx < 4; ++gap_idx) {
    int gap = shell_gaps[gap_idx];
    for (int i = gap; i < SORT_SIZE; ++i) {
      SORT_T key = SORT_AT(i);
      int j = i;
      while (j >= gap && SORT_GT(SORT_AT(j - gap), key)) {
        SORT_AT(j) = SORT_AT(j - gap);
        j -= gap;
      }
      SORT_AT(j) = key;
    }
  }
}

void sort_shell_offset() {
  for (int gap_idx = shell_start_gap(SORT_SIZE); gap_idx < 4; ++gap_idx) {
    int gap = shell_gaps[gap_idx];
    for (int i = gap; i < SORT_SIZE; ++i) {
      SORT_T key = SORT_AT(i);
      int j = i - gap;
      while (j >= 0 && SORT_GT(SORT_AT(j), key)) {
        SORT_AT(j + gap) = SORT_AT(j);
        j -= gap;
      }
      SORT_AT(j + gap) = key;
    }
  }
}
