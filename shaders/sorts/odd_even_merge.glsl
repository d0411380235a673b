// Batcher's odd-even merge sort network (Knowles 2014, 2.4), the iterative form that works for
// any size (comparators beyond the end are dropped; all put the element that belongs first at the
// lower index).
// Loops count in log2 so the unroller sees additive bounds.
#include "api.glsl"

void sort_odd_even_merge() {
  for (int log_p = 0; log_p < SORT_SIZE_LOG2; ++log_p) {
    int p = 1 << log_p;
    for (int log_k = log_p; log_k >= 0; --log_k) {
      int k = 1 << log_k;
      for (int j = k % p; j + k < SORT_SIZE; j += 2 * k)
        for (int i = 0; i < k; ++i)
          if (i + j + k < SORT_SIZE && (i + j) / (2 * p) == (i + j + k) / (2 * p) && SORT_GREATER(i + j, i + j + k))
            SORT_SWAP(i + j, i + j + k);
    }
  }
}
