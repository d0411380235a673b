// Insertion v1 (Brüll 2018, 4.5): Listing 4.11 with its dynamic write replaced by the select loop of
// Listing 4.7 - two consecutive loops per element. Diff against insertion_naive.glsl: only line 9 differs.
#include "frags.glsl"

#define SORT_ALGORITHM sort_insertion_v1

void sort_insertion_v1() {
  for (int i = 1; i < SORT_SIZE; ++i) {
    SORT_T key = SORT_AT(i);
    int j = i - 1;
    while (j >= 0 && SORT_GT(SORT_AT(j), key)) {
      SORT_AT(j + 1) = SORT_AT(j);
      --j;
    }
    for (int k = 0; k < SORT_SIZE; ++k)
      if (k == j + 1) SORT_AT(k) = key;
  }
}
