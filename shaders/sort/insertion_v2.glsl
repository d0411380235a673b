// Register insertion sort, insertion v2 (Brüll 2018 Listing 4.12): the key is swapped down into
// its place, so the shift loop and the final write become one loop whose indices are constants
// once both loops are unrolled.
#include "frags.glsl"

#define SORT_ALGORITHM sort_insertion_v2

void sort_insertion_v2() {
  for (int i = 1; i < SORT_SIZE; ++i)
    for (int j = i; j > 0 && SORT_GREATER(j - 1, j); --j) SORT_SWAP(j - 1, j);
}
