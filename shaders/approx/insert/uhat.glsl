// UHAT, section 6.4, Listing 6.1: unsorted relative transmittance, height metric against an
// exponential fit of the visibility function.
// Written against insert/api.glsl (included by approx/insert.frag under its TECH_ define).
float fT[N + 1];
float fZ[N + 1];

float visExponent = 0.0, visOffset = 0.0;
float vis(float x) { return exp(visExponent * (x + visOffset)); }
void insert(ivec2 p, vec4 c, vec4 ct, float z) {
  float maxDepth = z, minDepth = z;
  float productT = ct.a, lastT = ct.a;
  int maxIndex = N, minIndex = N;
  fT[N] = ct.a;
  fZ[N] = z;
  for (int i = 0; i < N; ++i) {
    uvec2 node = STORAGE_LOAD(p, i);
    fT[i] = at_transmittance(node);
    fZ[i] = node_depth(node);
    productT *= fT[i];
    if (fZ[i] > maxDepth) { maxDepth = fZ[i]; lastT = fT[i]; maxIndex = i; }
    if (fZ[i] < minDepth) { minDepth = fZ[i]; minIndex = i; }
  }
  if (maxDepth == DEPTH_EMPTY) {  // an initialisation node is left: no compression
    STORAGE_STORE(p, maxIndex, at_node(fT[N], z));
    return;
  }
  const float e = 0.00000001;
  visExponent = log(GUARD(productT / GUARD(lastT, e), e)) / GUARD(maxDepth - minDepth, e);
  visOffset = -minDepth;
  float minHeight = DEPTH_EMPTY;
  int removeIndex = minIndex == 0 ? 1 : 0;
  for (int i = 0; i <= N; ++i) {
    float h = vis(fZ[i]) * (1.0 - fT[i]) * (1.0 - fT[i]);  // Eq. 6.3
    if (h < minHeight && i != minIndex) { minHeight = h; removeIndex = i; }
  }
  // The predecessor: the nearest node at or before the removed one (the intent of Listing 6.1,
  // lines 65-75, whose comparison is reversed as printed; among equal depths the first found stays).
  int compressIndex = minIndex;
  for (int i = 0; i <= N; ++i)
    if (i != removeIndex && fZ[i] <= fZ[removeIndex] && fZ[i] > fZ[compressIndex]) compressIndex = i;
  float t = fT[compressIndex] * fT[removeIndex];
  if (compressIndex == N) {
    STORAGE_STORE(p, removeIndex, at_node(t, fZ[N]));
  } else {
    STORAGE_STORE(p, compressIndex, at_node(t, fZ[compressIndex]));
    if (removeIndex != N) STORAGE_STORE(p, removeIndex, at_node(fT[N], z));
  }
}
