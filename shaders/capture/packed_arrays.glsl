// Packed per-pixel arrays, PPPA (Knowles 2014 section 2.2; Maule et al.'s dynamic fragment
// buffer): the layout of fragment_storage.glsl under STORAGE_PPPA (bindings:
// micro/oit/capture/packed_arrays.hpp). A capture is two passes of the geometry:
//   STORAGE_PPPA_COUNT  counts each pixel's fragments (fragCounts)
//   (host)              an inclusive prefix sum of the counts gives each pixel's end, one past
//                       its last slot (fragOffsets), and its total sizes the fragment buffer exactly
//   STORAGE_PPPA_FILL   each fragment takes its pixel's last free slot: atomicAdd of -1 on
//                       fragOffsets, which so ends at the pixel's first fragment
// A pixel's fragments are then fragOffsets[i] .. fragOffsets[i] + fragCounts[p] - 1, the last to
// arrive first: the order a linked list, which prepends, holds them in (fragment_lists.glsl), so a
// front-to-back submission is stored far to near, already sorted, in both layouts. No next
// pointers, no contention on one global counter, and each pixel's fragments side by side.
#if defined(STORAGE_PPPA) && !defined(OIT_STORAGE_LINEARIZED)
#define OIT_STORAGE_LINEARIZED

layout(binding = CAPTURE_COUNTS_UNIT, r32ui) uniform coherent uimage2D fragCounts;
layout(std430, binding = CAPTURE_OFFSETS_BINDING) coherent buffer FragOffsets { uint fragOffsets[]; };

uint frag_pixel_index(ivec2 p) { return uint(p.y * imageSize(fragCounts).x + p.x); }

uint fragEnd;  // one past the current pixel's last fragment (set by FRAG_BEGIN)
uint frag_begin(ivec2 p) {
  uint first = fragOffsets[frag_pixel_index(p)];
  fragEnd = first + imageLoad(fragCounts, p).r;
  return first;
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
  uint slot = atomicAdd(fragOffsets[frag_pixel_index(p)], 0xffffffffu) - 1u;  // from the end down
  if (slot < poolSize) frag_store(slot, frag_pack(rgba, depth));
}
#else
#error "a PPPA capture program is either STORAGE_PPPA_COUNT or STORAGE_PPPA_FILL"
#endif
#endif

#endif
