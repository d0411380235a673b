// Bubble sort, Brüll 2018 Listing 4.10. SORT_BUBBLE_EARLY_OUT keeps line 11 (stop after a pass
// without swaps); without it every pass runs (Table A.3 compares the two).
#include "api.glsl"

void sort_bubble() {
  for (int n = SORT_SIZE; n > 1; --n) {
    bool sorted = true;
    for (int i = 0; i < n - 1; ++i) {
      if (SORT_GREATER(i, i + 1)) {
        SORT_SWAP(i, i + 1);
        sorted = false;
      }
    }
#if defined(SORT_BUBBLE_EARLY_OUT)
    if (sorted) break;
#endif
  }
}
