// Insertion sort of frags[0..n) (Knowles 2014, listing 1), far-to-near (descending depth): a list
// captured front-to-back arrives in this order and costs n steps; reverse order costs n^2/2.
// Expects: uvec2 frags[MAX_FRAGS] (local memory).
void sort_insertion(int n) {
  for (int j = 1; j < n; ++j) {
    uvec2 key = frags[j];
    int i = j - 1;
    while (i >= 0 && FRAG_FARTHER(key, frags[i])) {
      frags[i + 1] = frags[i];
      --i;
    }
    frags[i + 1] = key;
  }
}
