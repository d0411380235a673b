// Per-pixel linked lists, PPLL (Yang et al. 2010), the default layout of fragment_storage.glsl
// (bindings: micro/oit/capture/fragment_lists.hpp): a global atomic counter allocates nodes, an atomic
// exchange on the pixel's head pointer links them; next pointers live in a parallel buffer.
#if !defined(STORAGE_PPPA) && !defined(OIT_STORAGE_LINKED_LIST)
#define OIT_STORAGE_LINKED_LIST

layout(binding = CAPTURE_HEADS_UNIT, r32ui) uniform coherent uimage2D headPointers;
layout(binding = CAPTURE_NEXT_UNIT, r32ui) uniform uimageBuffer nodeNext;
FRAG_DECLARE_CHUNKS(1, r32ui, nodeNext_1, nodeNext_2, nodeNext_3)  // past one texel buffer (fragment_storage.glsl)
FRAG_CHUNKED_ACCESSORS(frag_next_words_, frag_set_next_words_, nodeNext, nodeNext_1, nodeNext_2, nodeNext_3)
uint frag_next(uint node) { return frag_next_words_(node).r; }
void frag_set_next(uint node, uint next) { frag_set_next_words_(node, uvec4(next)); }
#ifdef STORAGE_COUNTS
layout(binding = CAPTURE_COUNTS_UNIT, r32ui) uniform uimage2D fragCounts;
#endif

#define LIST_END 0xFFFFFFFFu
#define FRAG_BEGIN(p) imageLoad(headPointers, (p)).r
#define FRAG_VALID(node) ((node) != LIST_END)
#define FRAG_NEXT(node) frag_next(node)
#define FRAG_SCREEN_SIZE() imageSize(headPointers)

#ifdef STORAGE_CAPTURE
layout(binding = CAPTURE_COUNTER_BINDING, offset = 0) uniform atomic_uint fragCounter;
uniform uint poolSize;  // nodes past the pool are counted but not stored: the host renders again

void store_fragment(ivec2 p, vec4 rgba, float depth) {
  uint node = atomicCounterIncrement(fragCounter);
#ifdef STORAGE_COUNTS
  imageAtomicAdd(fragCounts, p, 1u);
#endif
  if (node < poolSize && !frag_fault_drop(p)) {
    frag_store(node, frag_pack(rgba, depth));
    frag_set_next(node, imageAtomicExchange(headPointers, p, node));
  }
}
#endif

#endif
