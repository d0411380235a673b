// Per-pixel linked lists behind a small storage API, so the capture, the resolves and the sorts
// never touch the layout directly (bindings match micro/oit/fragment_lists.hpp):
//   FRAG_BEGIN(p)      the first node of pixel p's list
//   FRAG_VALID(node)   false past the end of the list
//   FRAG_NEXT(node)    the node after `node`
//   FRAG_LOAD(node)    the fragment: uvec2(packUnorm4x8(RGBA), floatBitsToUint(depth))
//   FRAG_STORE(node, frag)  overwrites a node's fragment in place (RBS-G's sorted blocks)
//   store_fragment(p, rgba, depth)   (capture only, STORAGE_CAPTURE)
// Depths are gl_FragCoord.z >= 0, so comparing their bits as uints orders them like the floats.
#ifndef OIT_STORAGE_LINKED_LIST
#define OIT_STORAGE_LINKED_LIST

layout(binding = 0, r32ui) uniform coherent uimage2D headPointers;
layout(binding = 1, rg32ui) uniform uimageBuffer nodeData;
layout(binding = 2, r32ui) uniform uimageBuffer nodeNext;
#ifdef STORAGE_COUNTS
layout(binding = 3, r32ui) uniform uimage2D fragCounts;
#endif

#define LIST_END 0xFFFFFFFFu
#define FRAG_BEGIN(p) imageLoad(headPointers, (p)).r
#define FRAG_VALID(node) ((node) != LIST_END)
#define FRAG_NEXT(node) imageLoad(nodeNext, int(node)).r
#define FRAG_LOAD(node) imageLoad(nodeData, int(node)).rg
// True when fragment a goes before b in far-to-near order. Equal depths are ordered by colour bits
// (as the CPU reference does), so the result never depends on the list order, which on a GPU
// changes from frame to frame.
#define FRAG_FARTHER(a, b) ((a).y > (b).y || ((a).y == (b).y && (a).x > (b).x))
#define FRAG_STORE(node, frag) imageStore(nodeData, int(node), uvec4((frag), 0u, 0u))

#ifdef STORAGE_CAPTURE
layout(binding = 0, offset = 0) uniform atomic_uint fragCounter;
uniform uint poolSize;  // nodes past the pool are counted but not stored: the host renders again

void store_fragment(ivec2 p, vec4 rgba, float depth) {
  uint node = atomicCounterIncrement(fragCounter);
#ifdef STORAGE_COUNTS
  imageAtomicAdd(fragCounts, p, 1u);
#endif
  if (node < poolSize) {
    imageStore(nodeData, int(node), uvec4(packUnorm4x8(rgba), floatBitsToUint(depth), 0u, 0u));
    imageStore(nodeNext, int(node), uvec4(imageAtomicExchange(headPointers, p, node)));
  }
}
#endif

#endif
