// Shell sort, Brüll 2018 Listing 4.13, gaps {20, 9, 4, 1}: an insertion sort of each gap's
// interleaved sequences. The insertion of element i takes one of three shapes:
//   (default)          Listing 4.13 with the hole index j: `a[j] = a[j - gap]` ... `a[j] = key`.
//                      The listing decrements j before the shift (`j -= gap; a[j] = a[j - gap]`),
//                      which reads below the array; this is the textbook order (shift, then step),
//                      which the listing evidently meant.
//   SORT_SHELL_OFFSET  the same algorithm in Listing 4.11's shape: j trails the hole by one gap
//                      (`a[j + gap] = a[j]` ... `a[j + gap] = key`)
//   SORT_SHELL_SWAP    register shell sort, Listing 4.14: the swap form of insertion v2
//                      (insertion.glsl, SORT_INSERTION_SWAP), so every index is a constant once
//                      the loops are unrolled
// Mesa 22.3.6 llvmpipe miscompiles the default hole-index shape: the shifts are lost, even with
// gap == 1 and in either memory form, so the sort experiment's `shell` is reported invalid there;
// SORT_SHELL_OFFSET is compiled correctly.
#include "api.glsl"

#if defined(SORT_SHELL_OFFSET) && defined(SORT_SHELL_SWAP)
#error "choose at most one of SORT_SHELL_OFFSET and SORT_SHELL_SWAP"
#endif

const int shell_gaps[4] = int[4](20, 9, 4, 1);

int shell_start_gap(int size) { return size > 20 ? 0 : (size > 9 ? 1 : (size > 4 ? 2 : 3)); }

void sort_shell() {
  for (int gap_idx = shell_start_gap(SORT_SIZE); gap_idx < 4; ++gap_idx) {
    int gap = shell_gaps[gap_idx];
    for (int i = gap; i < SORT_SIZE; ++i) {
#if defined(SORT_SHELL_SWAP)
      for (int j = i; j >= gap && SORT_GREATER(j - gap, j); j -= gap) SORT_SWAP(j - gap, j);
#elif defined(SORT_SHELL_OFFSET)
      SORT_T key = SORT_AT(i);
      int j = i - gap;
      while (j >= 0 && SORT_GT(SORT_AT(j), key)) {
        SORT_AT(j + gap) = SORT_AT(j);
        j -= gap;
      }
      SORT_AT(j + gap) = key;
#else
      SORT_T key = SORT_AT(i);
      int j = i;
      while (j >= gap && SORT_GT(SORT_AT(j - gap), key)) {
        SORT_AT(j) = SORT_AT(j - gap);
        j -= gap;
      }
      SORT_AT(j) = key;
#endif
    }
  }
}
