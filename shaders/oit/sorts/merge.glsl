// Bottom-up merge sort of frags[0..n), far-to-near, stable; the left run of each merge is copied
// to a half-size scratch array (the deep-pixel sort of BMA's IMS, Knowles 2013).
// Expects: uvec2 frags[MAX_FRAGS].
uvec2 mergeLeft[(MAX_FRAGS + 1) / 2];
void sort_merge(int n) {
  for (int width = 1; width < n; width *= 2) {
    for (int lo = 0; lo + width < n; lo += 2 * width) {
      int mid = lo + width, hi = min(lo + 2 * width, n), nl = width;
      for (int k = 0; k < nl; ++k) mergeLeft[k] = frags[lo + k];
      int a = 0, b = mid, o = lo;
      while (a < nl && b < hi) {
        if (!FRAG_FARTHER(frags[b], mergeLeft[a])) frags[o++] = mergeLeft[a++];
        else frags[o++] = frags[b++];
      }
      while (a < nl) frags[o++] = mergeLeft[a++];
    }
  }
}
