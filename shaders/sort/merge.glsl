// Bottom-up merge sort (Knowles 2014, 2.1: the O(n log n) alternative for deeper pixels). The
// merge cursors index the arrays by data, so there is no register form: memory=local only.
#include "frags.glsl"

#define SORT_ALGORITHM sort_merge

SORT_T merge_tmp[SORT_N];

void sort_merge() {
  for (int width = 1; width < SORT_SIZE; width *= 2) {
    for (int lo = 0; lo < SORT_SIZE; lo += 2 * width) {
      int mid = min(lo + width, SORT_SIZE), hi = min(lo + 2 * width, SORT_SIZE);
      int a = lo, b = mid;
      for (int o = lo; o < hi; ++o) {
        // Take from the left run on ties: stable.
        if (b >= hi || (a < mid && !SORT_GT(SORT_AT(a), SORT_AT(b)))) merge_tmp[o] = SORT_AT(a++);
        else merge_tmp[o] = SORT_AT(b++);
      }
    }
    for (int i = 0; i < SORT_SIZE; ++i) SORT_AT(i) = merge_tmp[i];
  }
}
