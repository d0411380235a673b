// Every captured fragment of every pixel, behind one small API, so the capture, the resolves and
// the sorts never touch the layout (Knowles 2014, section 2.2). The host picks the layout with an
// injected define (micro/oit/capture/fragment_storage.hpp):
//   (default)     per-pixel linked lists, PPLL (fragment_lists.glsl)
//   STORAGE_PPPA  packed per-pixel arrays, PPPA: a count pass, a prefix sum, a fill pass
//                 (packed_arrays.glsl)
// The API:
//   FRAG_BEGIN(p)      the first fragment of pixel p (call it before the others for that pixel)
//   FRAG_VALID(node)   false past the pixel's last fragment
//   FRAG_NEXT(node)    the fragment after `node`
//   FRAG_LOAD(node)    the fragment, a FRAG_T (below: uvec2(packUnorm4x8(RGBA), depth bits) in RGBA8)
//   FRAG_STORE(node, frag)  overwrites a fragment in place (RBS-G's sorted blocks)
//   FRAG_FARTHER(a, b) true when fragment a goes before b in far-to-near order
//   FRAG_SCREEN_SIZE() the size of the captured image in pixels
//   store_fragment(p, rgba, depth)   (capture shaders only: STORAGE_CAPTURE)
// Depths are >= 0 (window or view depth), so comparing their bits as uints orders them like the floats.
// Both layouts keep the fragments in the same texel buffer (binding 1, and its chunks past one
// buffer's limit), so they differ only in how a pixel finds its fragments.
#ifndef OIT_STORAGE_FRAGMENTS
#define OIT_STORAGE_FRAGMENTS
#include "bindings.h"

// The fragment's format (micro/oit/capture/fragment_storage.hpp, docs/precision.md), one define of each:
//   FRAG_COLOUR_RGBA8 (default)  FRAG_T uvec2 (packUnorm4x8 colour, depth bits): the papers' 64-bit node
//   FRAG_COLOUR_RGBA16F          FRAG_T uvec3 (packHalf2x16 rg, depth bits, packHalf2x16 ba)
//   FRAG_COLOUR_RGBA32F          FRAG_T FragRGBA32F (float bits of rgba, depth bits)
//   FRAG_DEPTH_WINDOW (default)  the depth stored is gl_FragCoord.z
//   FRAG_DEPTH_VIEW              the view-space distance along the view axis (capture.frag)
// Wide colours keep their depths apart in nodeDepth (image unit 5), so a node is 8, 12 or 20 bytes.
//   FRAG_DEPTH_BITS(f)   the sort key: the depth's float bits (>= 0, so they compare as uints)
//   frag_colour(f)       the stored colour as vec4
//   frag_colour_greater(a, b)  equal depths' order: alpha, blue, green, red of the stored colour
// Past GL_MAX_TEXTURE_BUFFER_SIZE texels the node arrays are split into FRAG_CHUNKS texel buffers
// (micro/oit/capture/fragment_storage.hpp, at most 4) of 2^FRAG_CHUNK_SHIFT texels: node i lives in chunk
// i >> FRAG_CHUNK_SHIFT at offset i & (2^FRAG_CHUNK_SHIFT - 1). Chunk 0 keeps the layout's unit
// (1, 2, 5); chunk c > 0 is on unit 8 + 3 (c - 1) + (0 colours, 1 next pointers, 2 depths). Without
// FRAG_CHUNKS (one chunk) every access is the plain imageLoad/imageStore of before.
#ifndef FRAG_CHUNKS
#define FRAG_CHUNKS 1
#endif
#if FRAG_CHUNKS > 4
#error "the fragment storage binds at most 4 chunks"
#endif
#if FRAG_CHUNKS > 1
#define FRAG_CHUNK_OF(node) ((node) >> FRAG_CHUNK_SHIFT)
#define FRAG_OFFSET_OF(node) int((node) & ((1u << FRAG_CHUNK_SHIFT) - 1u))
// FRAG_CHUNKED_LOAD(result, name0, name1, name2, name3, node): result = imageLoad of the node's chunk.
#define FRAG_CHUNKED_LOAD(r, a0, a1, a2, a3, node)      \
  {                                                     \
    uint c_ = FRAG_CHUNK_OF(node);                      \
    int o_ = FRAG_OFFSET_OF(node);                      \
    if (c_ == 0u) r = imageLoad(a0, o_);                \
    else if (c_ == 1u || FRAG_CHUNKS == 2) r = imageLoad(a1, o_); \
    else FRAG_CHUNKED_LOAD_HIGH_(r, a2, a3, c_, o_)     \
  }
#define FRAG_CHUNKED_STORE(a0, a1, a2, a3, node, v)     \
  {                                                     \
    uint c_ = FRAG_CHUNK_OF(node);                      \
    int o_ = FRAG_OFFSET_OF(node);                      \
    if (c_ == 0u) imageStore(a0, o_, v);                \
    else if (c_ == 1u || FRAG_CHUNKS == 2) imageStore(a1, o_, v); \
    else FRAG_CHUNKED_STORE_HIGH_(a2, a3, c_, o_, v)    \
  }
#if FRAG_CHUNKS == 2
#define FRAG_CHUNKED_LOAD_HIGH_(r, a2, a3, c, o) {}
#define FRAG_CHUNKED_STORE_HIGH_(a2, a3, c, o, v) {}
#elif FRAG_CHUNKS == 3
#define FRAG_CHUNKED_LOAD_HIGH_(r, a2, a3, c, o) r = imageLoad(a2, o);
#define FRAG_CHUNKED_STORE_HIGH_(a2, a3, c, o, v) imageStore(a2, o, v);
#else
#define FRAG_CHUNKED_LOAD_HIGH_(r, a2, a3, c, o) \
  if (c == 2u) r = imageLoad(a2, o);              \
  else r = imageLoad(a3, o);
#define FRAG_CHUNKED_STORE_HIGH_(a2, a3, c, o, v) \
  if (c == 2u) imageStore(a2, o, v);               \
  else imageStore(a3, o, v);
#endif
#endif
// FRAG_CHUNKED_ACCESSORS(load, store, name0, name1, name2, name3): the functions uvec4 load(uint node)
// and void store(uint node, uvec4 v) of one chunked array (its images name0..name3; the plain
// imageLoad/imageStore of name0 with one chunk).
#if FRAG_CHUNKS > 1
#define FRAG_CHUNKED_ACCESSORS(load, store, a0, a1, a2, a3) \
  uvec4 load(uint node) {                                   \
    uvec4 r;                                                \
    FRAG_CHUNKED_LOAD(r, a0, a1, a2, a3, node)              \
    return r;                                               \
  }                                                         \
  void store(uint node, uvec4 v) { FRAG_CHUNKED_STORE(a0, a1, a2, a3, node, v) }
#else
#define FRAG_CHUNKED_ACCESSORS(load, store, a0, a1, a2, a3)    \
  uvec4 load(uint node) { return imageLoad(a0, int(node)); } \
  void store(uint node, uvec4 v) { imageStore(a0, int(node), v); }
#endif
// FRAG_DECLARE_CHUNK_(slot, format, name, chunk): the image of chunk `chunk` > 0 of one array.
#define FRAG_DECLARE_CHUNK_(slot, format, name, chunk) layout(binding = CAPTURE_CHUNK_UNIT_BASE + 3 * (chunk - 1) + slot, format) uniform uimageBuffer name;
// FRAG_DECLARE_CHUNKS(slot, format, name1, name2, name3): the images of one array's chunks past the
// first, FRAG_CHUNKS - 1 of them (the names of chunks that do not exist are never read: above, the
// accessors of FRAG_CHUNKS == 2 or 3 stop short of them).
#if FRAG_CHUNKS == 2
#define FRAG_DECLARE_CHUNKS(slot, format, a1, a2, a3) FRAG_DECLARE_CHUNK_(slot, format, a1, 1)
#elif FRAG_CHUNKS == 3
#define FRAG_DECLARE_CHUNKS(slot, format, a1, a2, a3) \
  FRAG_DECLARE_CHUNK_(slot, format, a1, 1) FRAG_DECLARE_CHUNK_(slot, format, a2, 2)
#elif FRAG_CHUNKS == 4
#define FRAG_DECLARE_CHUNKS(slot, format, a1, a2, a3)                              \
  FRAG_DECLARE_CHUNK_(slot, format, a1, 1) FRAG_DECLARE_CHUNK_(slot, format, a2, 2) \
  FRAG_DECLARE_CHUNK_(slot, format, a3, 3)
#else
#define FRAG_DECLARE_CHUNKS(slot, format, a1, a2, a3)
#endif

#if defined(FRAG_COLOUR_RGBA32F)
#define FRAG_DATA_FORMAT rgba32ui
#else
#define FRAG_DATA_FORMAT rg32ui
#endif
layout(binding = CAPTURE_NODES_UNIT, FRAG_DATA_FORMAT) uniform uimageBuffer nodeData;
#if defined(FRAG_COLOUR_RGBA32F) || defined(FRAG_COLOUR_RGBA16F)
#define FRAG_WIDE
layout(binding = CAPTURE_NODE_DEPTH_UNIT, r32ui) uniform uimageBuffer nodeDepth;
#endif
FRAG_DECLARE_CHUNKS(0, FRAG_DATA_FORMAT, nodeData_1, nodeData_2, nodeData_3)
#if defined(FRAG_WIDE)
FRAG_DECLARE_CHUNKS(2, r32ui, nodeDepth_1, nodeDepth_2, nodeDepth_3)
#endif

// The node's words as stored (colour words in .rg or .rgba; depth words apart for wide formats).
FRAG_CHUNKED_ACCESSORS(frag_data_load, frag_data_store, nodeData, nodeData_1, nodeData_2, nodeData_3)
#if defined(FRAG_WIDE)
FRAG_CHUNKED_ACCESSORS(frag_depth_words_load_, frag_depth_words_store_, nodeDepth, nodeDepth_1, nodeDepth_2, nodeDepth_3)
uint frag_depth_load(uint node) { return frag_depth_words_load_(node).r; }
void frag_depth_store(uint node, uint d) { frag_depth_words_store_(node, uvec4(d, 0u, 0u, 0u)); }
#endif

#if defined(FRAG_COLOUR_RGBA32F)
struct FragRGBA32F {
  uvec4 colour;
  uint depth;
};
#define FRAG_T FragRGBA32F
#define FRAG_ZERO FragRGBA32F(uvec4(0u), 0u)
FRAG_T frag_load(uint node) { return FRAG_T(frag_data_load(node), frag_depth_load(node)); }
void frag_store(uint node, FRAG_T f) {
  frag_data_store(node, f.colour);
  frag_depth_store(node, f.depth);
}
FRAG_T frag_pack(vec4 rgba, float depth) { return FRAG_T(floatBitsToUint(rgba), floatBitsToUint(depth)); }
vec4 frag_colour(FRAG_T f) { return uintBitsToFloat(f.colour); }
#define FRAG_DEPTH_BITS(f) ((f).depth)
bool frag_colour_greater(FRAG_T a, FRAG_T b) {
  if (a.colour.w != b.colour.w) return a.colour.w > b.colour.w;
  if (a.colour.z != b.colour.z) return a.colour.z > b.colour.z;
  if (a.colour.y != b.colour.y) return a.colour.y > b.colour.y;
  return a.colour.x > b.colour.x;
}
#elif defined(FRAG_COLOUR_RGBA16F)
#define FRAG_T uvec3
#define FRAG_ZERO uvec3(0u)
FRAG_T frag_load(uint node) {
  uvec2 c = frag_data_load(node).rg;
  return uvec3(c.x, frag_depth_load(node), c.y);
}
void frag_store(uint node, FRAG_T f) {
  frag_data_store(node, uvec4(f.x, f.z, 0u, 0u));
  frag_depth_store(node, f.y);
}
FRAG_T frag_pack(vec4 rgba, float depth) {
  return uvec3(packHalf2x16(rgba.rg), floatBitsToUint(depth), packHalf2x16(rgba.ba));
}
vec4 frag_colour(FRAG_T f) { return vec4(unpackHalf2x16(f.x), unpackHalf2x16(f.z)); }
#define FRAG_DEPTH_BITS(f) ((f).y)
bool frag_colour_greater(FRAG_T a, FRAG_T b) { return a.z > b.z || (a.z == b.z && a.x > b.x); }
#else
#define FRAG_T uvec2
#define FRAG_ZERO uvec2(0u)
FRAG_T frag_load(uint node) { return frag_data_load(node).rg; }
void frag_store(uint node, FRAG_T f) { frag_data_store(node, uvec4(f, 0u, 0u)); }
FRAG_T frag_pack(vec4 rgba, float depth) { return uvec2(packUnorm4x8(rgba), floatBitsToUint(depth)); }
vec4 frag_colour(FRAG_T f) { return unpackUnorm4x8(f.x); }
#define FRAG_DEPTH_BITS(f) ((f).y)
bool frag_colour_greater(FRAG_T a, FRAG_T b) { return a.x > b.x; }
#endif

#define FRAG_LOAD(node) frag_load(node)
#define FRAG_STORE(node, frag) frag_store(node, frag)
// Equal depths are ordered by colour (as the CPU reference does), so the result never depends on
// the order fragments were stored in, which on a GPU changes from frame to frame.
#define FRAG_FARTHER(a, b)                           \
  (FRAG_DEPTH_BITS(a) > FRAG_DEPTH_BITS(b) ||        \
   (FRAG_DEPTH_BITS(a) == FRAG_DEPTH_BITS(b) && frag_colour_greater(a, b)))

// fault=lose-fragment: the capture drops the fragments of the diagonal x == y, so the capture's
// own checks (every counted fragment stored, every list whole) must fail.
#ifdef OITBENCH_FAULT_LOSE_FRAGMENT
bool frag_fault_drop(ivec2 p) { return p.x == p.y; }
#else
bool frag_fault_drop(ivec2 p) { return false; }
#endif

#endif

// The shader library expands an include once, where it first appears, whatever #if surrounds it:
// each layout file guards its own body.
#include "fragment_lists.glsl"
#include "packed_arrays.glsl"
