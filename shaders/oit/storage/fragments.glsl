// Every captured fragment of every pixel, behind one small API, so the capture, the resolves and
// the sorts never touch the layout (Knowles 2014, section 2.2). The host picks the layout with an
// injected define (micro/oit/fragment_storage.hpp):
//   (default)     per-pixel linked lists, PPLL (storage/linked_list.glsl)
//   STORAGE_PPPA  packed per-pixel arrays, PPPA: a count pass, a prefix sum, a fill pass
//                 (storage/linearized.glsl)
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
// Both layouts keep the fragments in the same texel buffer (binding 1), so they differ only in how
// a pixel finds its fragments.
#ifndef OIT_STORAGE_FRAGMENTS
#define OIT_STORAGE_FRAGMENTS

// The fragment's format (micro/oit/fragment_storage.hpp, docs/precision.md), one define of each:
//   FRAG_COLOUR_RGBA8 (default)  FRAG_T uvec2 (packUnorm4x8 colour, depth bits): the papers' 64-bit node
//   FRAG_COLOUR_RGBA16F          FRAG_T uvec3 (packHalf2x16 rg, depth bits, packHalf2x16 ba)
//   FRAG_COLOUR_RGBA32F          FRAG_T FragRGBA32F (float bits of rgba, depth bits)
//   FRAG_DEPTH_WINDOW (default)  the depth stored is gl_FragCoord.z
//   FRAG_DEPTH_VIEW              the view-space distance along the view axis (capture.frag)
// Wide colours keep their depths apart in nodeDepth (image unit 5), so a node is 8, 12 or 20 bytes.
//   FRAG_DEPTH_BITS(f)   the sort key: the depth's float bits (>= 0, so they compare as uints)
//   frag_colour(f)       the stored colour as vec4
//   frag_colour_greater(a, b)  equal depths' order: alpha, blue, green, red of the stored colour
#if defined(FRAG_COLOUR_RGBA32F)
struct FragRGBA32F {
  uvec4 colour;
  uint depth;
};
#define FRAG_T FragRGBA32F
#define FRAG_ZERO FragRGBA32F(uvec4(0u), 0u)
layout(binding = 1, rgba32ui) uniform uimageBuffer nodeData;
layout(binding = 5, r32ui) uniform uimageBuffer nodeDepth;
FRAG_T frag_load(uint node) { return FRAG_T(imageLoad(nodeData, int(node)), imageLoad(nodeDepth, int(node)).r); }
void frag_store(uint node, FRAG_T f) {
  imageStore(nodeData, int(node), f.colour);
  imageStore(nodeDepth, int(node), uvec4(f.depth, 0u, 0u, 0u));
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
layout(binding = 1, rg32ui) uniform uimageBuffer nodeData;
layout(binding = 5, r32ui) uniform uimageBuffer nodeDepth;
FRAG_T frag_load(uint node) {
  uvec2 c = imageLoad(nodeData, int(node)).rg;
  return uvec3(c.x, imageLoad(nodeDepth, int(node)).r, c.y);
}
void frag_store(uint node, FRAG_T f) {
  imageStore(nodeData, int(node), uvec4(f.x, f.z, 0u, 0u));
  imageStore(nodeDepth, int(node), uvec4(f.y, 0u, 0u, 0u));
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
layout(binding = 1, rg32ui) uniform uimageBuffer nodeData;
FRAG_T frag_load(uint node) { return imageLoad(nodeData, int(node)).rg; }
void frag_store(uint node, FRAG_T f) { imageStore(nodeData, int(node), uvec4(f, 0u, 0u)); }
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
#include "linked_list.glsl"
#include "linearized.glsl"
