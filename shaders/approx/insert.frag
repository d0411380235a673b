// Pass 1 of the per-pixel array techniques: every fragment is inserted into its pixel's n nodes
// under the per-pixel spinlock of Listing 4.3 (helper invocations skip it; the spin gives up after
// SPIN_CAP tries and counts itself, so a lost insertion is reported, never a hang).
//   TECH_MLAB   Listing 3.1: one bubble pass, merge the last two nodes, store all n
//   TECH_UMLAB  Listing 5.1 + 5.2: unsorted, merge the two farthest, store at most two nodes
//   TECH_AT     section 3.6: sorted absolute transmittance, rect metric, underestimation
//   TECH_HAT    section 6.3: AT with the height metric (Eq. 6.1)
//   TECH_UAT    section 6.1: unsorted relative transmittance, sorted in registers, rect metric
//   TECH_UHAT   section 6.4, Listing 6.1: unsorted relative transmittance, height metric against an
//               exponential fit of the visibility function
//   TECH_HT     hybrid transparency's core (Maule et al. 2013): a k-buffer of the n nearest
//               fragments whole (RGBA8 colour, depth), in (depth, colour) order; a fragment pushed
//               out goes to the tail, which approx/ht_tail.frag accumulates in a second pass
//   TECH_LAAT   section 6.2: UAT's relative nodes linked into a list (a link per node, a head
//               slot), walked instead of sorted; only the changed nodes are written back
// SYNC_INTERLOCK replaces the spinlock by ARB_fragment_shader_interlock (ordered: the insertion
// order becomes the submission order on any GPU; llvmpipe lacks it and reports `unsupported`).
// APPROX_UNGUARDED removes the numeric guards (UHAT's divisions and logarithm, HAT's division):
// the hard-case tests prove the guards matter.
#if defined(SYNC_INTERLOCK)
#extension GL_ARB_fragment_shader_interlock : require
#endif
#include "../common/oitbench.glsl"
#include "../storage/storage.glsl"
#include "nodes.glsl"
#include "../oit/shade.glsl"
#include "bindings.h"
// The opaque effect's depth test must come before the node stores (a hidden fragment is never
// inserted); without a depth attachment this changes nothing.
layout(early_fragment_tests) in;

in vec4 vColour;
in vec2 vUv;
in float vSoft;
in vec3 vWorld;
uniform int zero;
#if defined(SYNC_INTERLOCK)
layout(pixel_interlock_ordered) in;
#endif

layout(r32ui, binding = APPROX_LOCK_IMAGE_UNIT) coherent uniform uimage2D locks;
layout(std430, binding = APPROX_STATS_BINDING) buffer ApproxStats { uint cappedUpdates; };

#if defined(APPROX_UNGUARDED)
#define GUARD(x, lo) (x)
#else
#define GUARD(x, lo) max(x, lo)
#endif

#if defined(TECH_MLAB) || defined(TECH_UMLAB)
vec4 fC[N + 1];  // (C, T)
float fZ[N + 1];
vec4 merge(vec4 a, vec4 b) { return vec4(a.rgb + a.a * b.rgb, a.a * b.a); }
#else
float fT[N + 1];
float fZ[N + 1];
#endif

#if defined(TECH_MLAB)
void insert(ivec2 p, vec4 ct, float z) {
  fC[0] = ct;
  fZ[0] = z;
  for (int i = 0; i < N; ++i) {
    uvec2 node = STORAGE_LOAD(p, i);
    fC[i + 1] = mlab_value(node);
    fZ[i + 1] = node_depth(node);
  }
  for (int i = 0; i < N; ++i) {
    if (fZ[i] > fZ[i + 1]) {
      vec4 tc = fC[i]; fC[i] = fC[i + 1]; fC[i + 1] = tc;
      float tz = fZ[i]; fZ[i] = fZ[i + 1]; fZ[i + 1] = tz;
    }
  }
  fC[N - 1] = merge(fC[N - 1], fC[N]);
  for (int i = 0; i < N; ++i) STORAGE_STORE(p, i, mlab_node(fC[i], fZ[i]));
}

#elif defined(TECH_UMLAB)
void insert(ivec2 p, vec4 ct, float z) {
  fC[N] = ct;
  fZ[N] = z;
  for (int i = 0; i < N; ++i) {
    uvec2 node = STORAGE_LOAD(p, i);
    fC[i] = mlab_value(node);
    fZ[i] = node_depth(node);
  }
  int maxIdx = 0;
  float maxZ = -1.0;
  for (int i = 0; i <= N; ++i)
    if (fZ[i] > maxZ) { maxZ = fZ[i]; maxIdx = i; }
  if (maxZ == DEPTH_EMPTY) {  // Listing 5.2: an initialisation node is left, no merge
    STORAGE_STORE(p, maxIdx, mlab_node(ct, z));
    return;
  }
  int smaxIdx = 0;
  float smaxZ = -1.0;
  for (int i = 0; i <= N; ++i)
    if (fZ[i] > smaxZ && i != maxIdx) { smaxZ = fZ[i]; smaxIdx = i; }
  vec4 merged = merge(fC[smaxIdx], fC[maxIdx]);
  if (maxIdx == N) {
    maxIdx = smaxIdx;
    smaxIdx = N;
  }
  STORAGE_STORE(p, maxIdx, mlab_node(merged, smaxZ));
  if (smaxIdx != N) STORAGE_STORE(p, smaxIdx, mlab_node(ct, z));
}

#elif defined(TECH_AT) || defined(TECH_HAT)
void insert(ivec2 p, vec4 ct, float z) {
  float a = ct.a;  // the fragment's transmittance
  int k = 0;             // insertion position: after the nodes at the same or smaller depth
  for (int i = 0; i < N; ++i) {
    uvec2 node = STORAGE_LOAD(p, i);
    fT[i] = at_transmittance(node);
    fZ[i] = node_depth(node);
    if (fZ[i] <= z) k = i + 1;
  }
  for (int i = N; i > k; --i) {
    fT[i] = fT[i - 1] * a;
    fZ[i] = fZ[i - 1];
  }
  fT[k] = (k > 0 ? fT[k - 1] : 1.0) * a;
  fZ[k] = z;
  if (fZ[N] != DEPTH_EMPTY) {
    // Compress: remove the node r (never the first) with the least error, underestimating:
    // its predecessor takes its transmittance.
    int r = 1;
    float best = DEPTH_EMPTY;
    for (int i = 1; i <= N; ++i) {
      float h = fT[i - 1] - fT[i];
#if defined(TECH_AT)
      float e = (fZ[i] - fZ[i - 1]) * h;  // rect metric
#else
      float e = h * h / GUARD(fT[i - 1], 1e-30);  // height metric, Eq. 6.1
#endif
      if (e < best) { best = e; r = i; }
    }
    fT[r - 1] = fT[r];
    for (int i = r; i < N; ++i) {
      fT[i] = fT[i + 1];
      fZ[i] = fZ[i + 1];
    }
  }
  for (int i = 0; i < N; ++i) STORAGE_STORE(p, i, at_node(fT[i], fZ[i]));
}

#elif defined(TECH_UAT)
int order[N + 1];
void insert(ivec2 p, vec4 ct, float z) {
  fT[N] = ct.a;
  fZ[N] = z;
  int empty = -1;
  for (int i = 0; i < N; ++i) {
    uvec2 node = STORAGE_LOAD(p, i);
    fT[i] = at_transmittance(node);
    fZ[i] = node_depth(node);
    if (empty < 0 && fZ[i] == DEPTH_EMPTY) empty = i;
  }
  if (empty >= 0) {
    STORAGE_STORE(p, empty, at_node(fT[N], z));
    return;
  }
  // Sort the node indices by depth (ties: by slot, the new fragment last) in registers.
  for (int i = 0; i <= N; ++i) order[i] = i;
  for (int i = 1; i <= N; ++i)
    for (int j = i; j > 0; --j) {
      int a = order[j - 1], b = order[j];
      if (fZ[a] > fZ[b] || (fZ[a] == fZ[b] && a > b)) { order[j - 1] = b; order[j] = a; }
    }
  // Rect metric on the absolute visibility (prefix products of the relative transmittances).
  float before = fT[order[0]];
  int r = 1;
  float best = DEPTH_EMPTY;
  for (int i = 1; i <= N; ++i) {
    float after = before * fT[order[i]];
    float e = (fZ[order[i]] - fZ[order[i - 1]]) * (before - after);
    if (e < best) { best = e; r = i; }
    before = after;
  }
  int removeIdx = order[r], compressIdx = order[r - 1];
  float t = fT[compressIdx] * fT[removeIdx];
  if (compressIdx == N) {
    STORAGE_STORE(p, removeIdx, at_node(t, fZ[N]));
  } else {
    STORAGE_STORE(p, compressIdx, at_node(t, fZ[compressIdx]));
    if (removeIdx != N) STORAGE_STORE(p, removeIdx, at_node(fT[N], z));
  }
}

#elif defined(TECH_UHAT)
float visExponent = 0.0, visOffset = 0.0;
float vis(float x) { return exp(visExponent * (x + visOffset)); }
void insert(ivec2 p, vec4 ct, float z) {
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
#elif defined(TECH_LAAT)
#define LAAT_N (STORAGE_NODES - 1)
#define LAAT_HEAD LAAT_N
uvec2 old[LAAT_N];
int walk[LAAT_N];      // slots in list order, as walked
int seq[LAAT_N + 1];   // slots near to far; slot LAAT_N stands for the new fragment
uvec2 laat_node(float t, float z, int next) {
  return uvec2(((floatBitsToUint(t) ^ ONE_BITS) & ~31u) | uint(next + 1), encode_depth(z));
}
void insert(ivec2 p, vec4 ct, float z) {
  uint head = STORAGE_LOAD(p, LAAT_HEAD).x;
  int cnt = 0, k = 0;
  int slot = int(head) - 1;
  for (int i = 0; i < LAAT_N && slot >= 0; ++i) {  // walk the list: random reads
    uvec2 node = STORAGE_LOAD(p, slot);
    old[slot] = node;
    fT[slot] = at_transmittance(node);
    fZ[slot] = node_depth(node);
    if (fZ[slot] <= z) k = cnt + 1;
    walk[cnt++] = slot;
    slot = int(node.x & 31u) - 1;
  }
  fT[LAAT_N] = ct.a;
  fZ[LAAT_N] = z;
  // Built into a second array: shifting `seq` in place (descending loop here, ascending after the
  // compression) gave wrong lists on llvmpipe, which the CPU model caught; the cause is not isolated.
  for (int i = 0; i <= cnt; ++i) seq[i] = i < k ? walk[i] : (i == k ? LAAT_N : walk[i - 1]);
  int len = cnt + 1;
  int newSlot = cnt;  // not full: the next free slot
  if (cnt == LAAT_N) {
    float before = fT[seq[0]];
    int r = 1;
    float best = DEPTH_EMPTY;
    for (int i = 1; i <= LAAT_N; ++i) {
      float after = before * fT[seq[i]];
      float e = (fZ[seq[i]] - fZ[seq[i - 1]]) * (before - after);
      if (e < best) { best = e; r = i; }
      before = after;
    }
    int compress = seq[r - 1], removed = seq[r];
    float t = fT[compress] * fT[removed];
    fT[compress] = t;
    newSlot = removed;  // the new fragment takes the removed node's slot (unless it was removed)
    len = LAAT_N;
    for (int i = 0; i < LAAT_N; ++i) walk[i] = i < r ? seq[i] : seq[i + 1];
  } else {
    for (int i = 0; i < len; ++i) walk[i] = seq[i];
  }
  // Write back what changed: the links around the new node, the compressed node, the head.
  for (int i = 0; i < len; ++i) {
    int s = walk[i];
    int next = i + 1 < len ? (walk[i + 1] == LAAT_N ? newSlot : walk[i + 1]) : -1;
    int at = s == LAAT_N ? newSlot : s;
    uvec2 node = laat_node(fT[s], fZ[s], next);
    if (s == LAAT_N || node != old[s]) STORAGE_STORE(p, at, node);
  }
  uint first = uint((walk[0] == LAAT_N ? newSlot : walk[0]) + 1);
  if (first != head) STORAGE_STORE(p, LAAT_HEAD, uvec2(first, 0u));
}
#elif defined(TECH_HT)
// Sorted insertion: the new fragment takes the first slot it precedes and pushes the rest back;
// the last node falls out of the core (into the tail, which is found again in the tail pass).
void insert(ivec2 p, uint key, float z) {
  for (int i = 0; i < N; ++i) {
    uvec2 node = STORAGE_LOAD(p, i);
    float nz = node_depth(node);
    if (z < nz || (z == nz && key < node.x)) {
      STORAGE_STORE(p, i, uvec2(key, encode_depth(z)));
      if (nz == DEPTH_EMPTY) break;
      key = node.x;
      z = nz;
    }
  }
}
#else
#error "define TECH_MLAB, TECH_UMLAB, TECH_AT, TECH_HAT, TECH_UAT, TECH_UHAT, TECH_LAAT or TECH_HT"
#endif

#if defined(TECH_HT)
#define INSERT_FRAGMENT insert(p, packUnorm4x8(c), z)
#else
#define INSERT_FRAGMENT insert(p, ct, z)
#endif

void main() {
  vec4 c = approx_fragment_colour(shade_fragment(vColour, vWorld), vUv, vSoft);
  ivec2 p = ivec2(gl_FragCoord.xy);
  float z = gl_FragCoord.z + oitbench_fault_hang(zero);
  vec4 ct = vec4(c.rgb * c.a, 1.0 - c.a);  // (premultiplied colour C, transmittance T)
#if defined(SYNC_INTERLOCK)
  beginInvocationInterlockARB();
  INSERT_FRAGMENT;
  endInvocationInterlockARB();
#else
  if (!gl_HelperInvocation) {
    bool waiting = true;
    for (uint spins = 0u; waiting && spins < uint(SPIN_CAP); ++spins) {
      if (imageAtomicCompSwap(locks, p, 0u, 1u) == 0u) {
        INSERT_FRAGMENT;
        memoryBarrier();
        imageAtomicExchange(locks, p, 0u);
        waiting = false;
      }
    }
    if (waiting) atomicAdd(cappedUpdates, 1u);
  }
#endif
}
