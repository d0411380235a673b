// Storage layouts (Brüll 2018, section 4.1, Table 4.1): the same per-pixel read-modify-write
// written once against the storage API; the layout is the injected STORAGE_* define.
// Every fragment loads its pixel's STORAGE_NODES nodes into a local array (as MLAB does), adds
// its contribution to each node and stores them all back. Node = (sum, count): the sum grows by
// a value fixed per (pixel, node) and the count by one, so the result does not depend on the
// order of fragments, any whole-node write is self-consistent (sum == count * value), and a
// lost update shows as a count below the number of layers.
//   ORDER_SCATTERED: the stores go out in a per-fragment rotated order (scattered writes, the
//                    pattern the thesis blames for UMLAB's lost updates with interleaved storage).
#include "../common/oitbench.glsl"
#include "../storage/storage.glsl"

uniform int zero;  // always 0; unknown to the compiler
flat in int layer;

// The same function as layout_node_value() in micro/experiments/layout.cpp.
uint node_value(ivec2 p, int i) { return ((uint(p.x) * 73856093u) ^ (uint(p.y) * 19349663u) ^ (uint(i) * 83492791u)) | 1u; }

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  uvec2 nodes[STORAGE_NODES];
  for (int i = 0; i < STORAGE_NODES; ++i) nodes[i] = STORAGE_LOAD(p, i);
  for (int i = 0; i < STORAGE_NODES; ++i) nodes[i] += uvec2(node_value(p, i), 1u);
#ifdef OITBENCH_FAULT_WRONG_RESULT
  if (p == ivec2(1, 1)) nodes[0].x += 1u;  // one node off by one: the validator must notice
#endif
  nodes[0].x += uint(oitbench_fault_hang(zero));  // no colour output: the stores are the result
#if defined(ORDER_SCATTERED)
  int rotation = (layer * 7 + p.x + p.y + zero) % STORAGE_NODES;
  for (int k = 0; k < STORAGE_NODES; ++k) {
    int i = (k + rotation) % STORAGE_NODES;
    STORAGE_STORE(p, i, nodes[i]);
  }
#else
  for (int i = 0; i < STORAGE_NODES; ++i) STORAGE_STORE(p, i, nodes[i]);
#endif
}
