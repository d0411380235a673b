// Inserting one element into a sorted array (Brüll 2018, 4.4): frags[1..SIZE-1] are sorted and the
// new element sits at frags[0]; it is moved up to its place. One function per listing:
//   insert_early_out     Listing 4.8: swap, stop at the first pair in order
//   insert_no_early_out  Listing 4.9: swap where out of order, never stop
//   insert_two_moves     Listing A.1: two moves instead of a swap (the new element is known), never stop
// Written against the sort library's element API (shaders/sorts/api.glsl), bound to the pixel's
// array by the sort experiment's binding (shaders/sort/frags.glsl). These are insertion steps into
// an array already sorted, not sorts, so they live with their experiment.
#include "../sorts/api.glsl"
#include "../sort/frags.glsl"

void insert_early_out(SORT_T e) {
  for (int i = 0; i < SORT_SIZE - 1; ++i) {
    if (!SORT_GREATER(i, i + 1)) break;
    SORT_SWAP(i, i + 1);
  }
}

void insert_no_early_out(SORT_T e) {
  for (int i = 0; i < SORT_SIZE - 1; ++i)
    if (SORT_GREATER(i, i + 1)) SORT_SWAP(i, i + 1);
}

void insert_two_moves(SORT_T e) {
  for (int i = 0; i < SORT_SIZE - 1; ++i) {
    if (SORT_GT(e, SORT_AT(i + 1))) {
      SORT_AT(i) = SORT_AT(i + 1);
      SORT_AT(i + 1) = e;
    }
  }
}
