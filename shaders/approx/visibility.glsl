// The visibility function vis(z) (Eq. 2.3) stored by the AT family: the transmittance in front of
// depth z (nodes strictly nearer than z). Sorted absolute nodes (AT, HAT): the last nearer node's
// value; relative nodes (UAT, UHAT, chapter 6): the product of the nearer nodes' values.
#include "nodes.glsl"
float visibility(ivec2 p, float z) {
  float v = 1.0;
  for (int i = 0; i < N; ++i) {
    uvec2 node = STORAGE_LOAD(p, i);
    float t = at_transmittance(node);
    if (node_depth(node) < z) {
#if defined(TECH_AT) || defined(TECH_HAT)
      v = t;
#else
      v *= t;
#endif
    }
  }
  return v;
}
