// Insertion sort: Brüll 2018 Listing 4.11, which is Knowles 2014 Listing 1 (the OIT resolves' IS,
// and the first stage of IMS). The final write a[j+1] = key (line 9) uses a data-dependent j; how
// it is written is Table A.1:
//   SORT_ASSIGN_DIRECT   SORT_AT(j + 1) = key (the listing; the default): with a dynamic j the
//                        array must be indexable, so it lives in local memory
//   SORT_ASSIGN_LOOP     an unrollable select loop (Listing 4.7): Brüll's insertion v1
//   SORT_ASSIGN_SWITCH   a switch with one constant-index case per element
//   SORT_ASSIGN_IF_ELSE  an if / else-if chain with one constant-index arm per element
// SORT_INSERTION_SWAP instead is Brüll's register insertion sort, insertion v2 (Listing 4.12): the
// key is swapped down into its place, so the shift loop and the final write become one loop whose
// indices are constants once both loops are unrolled.
// SWITCH and IF_ELSE expand over SORT_EACH_INDEX: the binding includes sorts/unroll.glsl (SORT_N <= 32).
#include "api.glsl"

#if defined(SORT_ASSIGN_DIRECT) + defined(SORT_ASSIGN_LOOP) + defined(SORT_ASSIGN_SWITCH) + \
        defined(SORT_ASSIGN_IF_ELSE) + defined(SORT_INSERTION_SWAP) > 1
#error "choose at most one of SORT_ASSIGN_DIRECT, _LOOP, _SWITCH, _IF_ELSE and SORT_INSERTION_SWAP"
#endif
#if (defined(SORT_ASSIGN_SWITCH) || defined(SORT_ASSIGN_IF_ELSE)) && !defined(SORT_EACH_INDEX)
#error "SORT_ASSIGN_SWITCH and SORT_ASSIGN_IF_ELSE need sorts/unroll.glsl included after SORT_N (<= 32)"
#endif

#define SORT_ASSIGN_CASE_(k) \
  case k:                    \
    SORT_AT(k) = key;        \
    break;
#define SORT_ASSIGN_IF_(k) else if (dest == k) SORT_AT(k) = key;

void sort_insertion() {
  for (int i = 1; i < SORT_SIZE; ++i) {
#if defined(SORT_INSERTION_SWAP)
    for (int j = i; j > 0 && SORT_GREATER(j - 1, j); --j) SORT_SWAP(j - 1, j);
#else
    SORT_T key = SORT_AT(i);
    int j = i - 1;
    while (j >= 0 && SORT_GT(SORT_AT(j), key)) {
      SORT_AT(j + 1) = SORT_AT(j);
      --j;
    }
    int dest = j + 1;
#if defined(SORT_ASSIGN_LOOP)
    for (int k = 0; k < SORT_SIZE; ++k)
      if (k == dest) SORT_AT(k) = key;
#elif defined(SORT_ASSIGN_SWITCH)
    switch (dest) { SORT_EACH_INDEX(SORT_ASSIGN_CASE_) }
#elif defined(SORT_ASSIGN_IF_ELSE)
    if (false) {
    }
    SORT_EACH_INDEX(SORT_ASSIGN_IF_)
#else  // SORT_ASSIGN_DIRECT
    SORT_AT(dest) = key;
#endif
#endif
  }
}
