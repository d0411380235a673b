// Bitonic sort network (Knowles 2014, 2.4), in the form whose comparators all put the element
// that belongs first at the lower index: the first step of each merge compares i with i ^ (k - 1), the rest with
// i ^ j. Comparators reaching past the end are dropped, which equals padding with elements that belong last to the
// next power of two, so any size works. Loops count in log2 so the unroller sees additive bounds.
#include "api.glsl"

void sort_bitonic() {
  for (int log_k = 1; log_k <= SORT_SIZE_LOG2; ++log_k) {
    int k = 1 << log_k;
    for (int log_j = log_k - 1; log_j >= 0; --log_j) {
      int j = 1 << log_j;
      for (int i = 0; i < SORT_SIZE; ++i) {
        int l = log_j == log_k - 1 ? (i ^ (k - 1)) : (i ^ j);
        if (l > i && l < SORT_SIZE && SORT_GREATER(i, l)) SORT_SWAP(i, l);
      }
    }
  }
}
