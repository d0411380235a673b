// Packed per-pixel arrays, PPPA (Knowles 2014 section 2.2; Maule et al.'s dynamic fragment
// buffer): the layout of fragment_storage.glsl under STORAGE_PPPA (bindings:
// micro/oit/capture/packed_arrays.hpp). A capture is two passes of the geometry:
//   STORAGE_PPPA_COUNT  counts each pixel's fragments (fragCounts)
//   (host)              an exclusive prefix sum of the counts gives each pixel's first slot
//                       (fragOffsets), and its total sizes the fragment buffer exactly
//   STORAGE_PPPA_FILL   each fragment takes the next slot of its pixel: atomicAdd on fragOffsets,
//                       which so ends one past the pixel's last fragment
// A pixel's fragments are then fragOffsets[i] - fragCounts[p] .. fragOffsets[i] - 1: no next
// pointers, no contention on one global counter, and each pixel's fragments side by side.
#if defined(STORAGE_PPPA) && !defined(OIT_STORAGE_LINEARIZED)
#define OIT_STORAGE_LINEARIZED

layout(binding = CAPTURE_COUNTS_UNIT, r32ui) uniform coherent uimage2D fragCounts;
layout(std430, binding = CAPTURE_OFFSETS_BINDING) coherent buffer FragOffsets { uint fragOffsets[]; };

uint frag_pixel_index(ivec2 p) { return uint(p.y * imageSize(fragCounts).x + p.x); }

uint fragEnd;  // one past the current pixel's last fragment (set by FRAG_BEGIN)
uint frag_begin(ivec2 p) {
  fragEnd = fragOffsets[frag_pixel_index(p)];
  return fragEnd - imageLoad(fragCounts, p).r;
}

#define FRAG_BEGIN(p) frag_begin(p)
#define FRAG_VALID(node) ((node) < fragEnd)
#define FRAG_NEXT(node) ((node) + 1u)
#define FRAG_SCREEN_SIZE() imageSize(fragCounts)

#ifdef STORAGE_CAPTURE
#if defined(STORAGE_PPPA_COUNT)
void store_fragment(ivec2 p, vec4 rgba, float depth) { imageAtomicAdd(fragCounts, p, 1u); }
#elif defined(STORAGE_PPPA_FILL)
uniform uint poolSize;  // the scan's total, so this never drops a fragment; a guard all the same
void store_fragment(ivec2 p, vec4 rgba, float depth) {
  if (frag_fault_drop(p)) return;
  uint slot = atomicAdd(fragOffsets[frag_pixel_index(p)], 1u);
  if (slot < poolSize) frag_store(slot, frag_pack(rgba, depth));
}
#else
#error "a PPPA capture program is either STORAGE_PPPA_COUNT or STORAGE_PPPA_FILL"
#endif
#endif

#endif
