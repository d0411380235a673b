// Bottom-up merge sort, stable (equal elements keep their order). The merge cursors index the
// array by data, so there is no register form: SORT_SIZE is a run-time value wherever it runs.
// Two papers' forms:
//   (default)                 Knowles 2014, 2.1 (the sort experiment's `merge`): every pass merges
//                             pairs of runs into a full-size temporary array (SORT_N elements),
//                             then copies it back
//   SORT_MERGE_HALF_SCRATCH   Knowles 2013, the deep-pixel half of IMS (the oit resolves): the
//                             left run of each merge is copied into a half-size scratch array
//                             ((SORT_N + 1) / 2 elements) and merged with the right run in place
#include "api.glsl"

#if defined(SORT_MERGE_HALF_SCRATCH)
SORT_T merge_left[(SORT_N + 1) / 2];

void sort_merge() {
  for (int width = 1; width < SORT_SIZE; width *= 2) {
    for (int lo = 0; lo + width < SORT_SIZE; lo += 2 * width) {
      int mid = lo + width, hi = min(lo + 2 * width, SORT_SIZE), nl = width;
      for (int k = 0; k < nl; ++k) merge_left[k] = SORT_AT(lo + k);
      int a = 0, b = mid, o = lo;
      while (a < nl && b < hi) {
        // Take from the left run on ties: stable.
        if (!SORT_GT(merge_left[a], SORT_AT(b))) SORT_AT(o++) = merge_left[a++];
        else SORT_AT(o++) = SORT_AT(b++);
      }
      while (a < nl) SORT_AT(o++) = merge_left[a++];
    }
  }
}
#else
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
#endif
