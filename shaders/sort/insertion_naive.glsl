// Standard insertion sort, Brüll 2018 Listing 4.11 (Knowles 2014 Listing 1, the baseline). The
// final write a[j+1] = key (line 9) uses a data-dependent j; how it is written is Table A.1:
//   SORT_ASSIGN_DIRECT   frags[j + 1] = key (the listing): forces the array into local memory
//   SORT_ASSIGN_LOOP     an unrollable select loop (Listing 4.7); with constant bounds this is insertion v1
//   SORT_ASSIGN_SWITCH   a switch with one constant-index case per element
//   SORT_ASSIGN_IF_ELSE  an if / else-if chain with one constant-index arm per element
// Without a choice, the listing's own direct write.
#include "frags.glsl"

#define SORT_ALGORITHM sort_insertion_naive
#include "unroll.glsl"

#if !defined(SORT_ASSIGN_LOOP) && !defined(SORT_ASSIGN_SWITCH) && !defined(SORT_ASSIGN_IF_ELSE)
#define SORT_ASSIGN_DIRECT
#endif

#define SORT_ASSIGN_CASE_(k) \
  case k:                    \
    SORT_AT(k) = key;        \
    break;
#define SORT_ASSIGN_IF_(k) else if (dest == k) SORT_AT(k) = key;

void sort_insertion_naive() {
  for (int i = 1; i < SORT_SIZE; ++i) {
    SORT_T key = SORT_AT(i);
    int j = i - 1;
    while (j >= 0 && SORT_GT(SORT_AT(j), key)) {
      SORT_AT(j + 1) = SORT_AT(j);
      --j;
    }
    int dest = j + 1;
#if defined(SORT_ASSIGN_DIRECT)
    SORT_AT(dest) = key;
#elif defined(SORT_ASSIGN_LOOP)
    for (int k = 0; k < SORT_SIZE; ++k)
      if (k == dest) SORT_AT(k) = key;
#elif defined(SORT_ASSIGN_SWITCH)
    switch (dest) { SORT_EACH_INDEX(SORT_ASSIGN_CASE_) }
#elif defined(SORT_ASSIGN_IF_ELSE)
    if (false) {
    }
    SORT_EACH_INDEX(SORT_ASSIGN_IF_)
#endif
  }
}
