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
//   FRAG_LOAD(node)    the fragment: uvec2(packUnorm4x8(RGBA), floatBitsToUint(depth))
//   FRAG_STORE(node, frag)  overwrites a fragment in place (RBS-G's sorted blocks)
//   FRAG_FARTHER(a, b) true when fragment a goes before b in far-to-near order
//   FRAG_SCREEN_SIZE() the size of the captured image in pixels
//   store_fragment(p, rgba, depth)   (capture shaders only: STORAGE_CAPTURE)
// Depths are gl_FragCoord.z >= 0, so comparing their bits as uints orders them like the floats.
// Both layouts keep the fragments in the same texel buffer (binding 1), so they differ only in how
// a pixel finds its fragments.
#ifndef OIT_STORAGE_FRAGMENTS
#define OIT_STORAGE_FRAGMENTS

layout(binding = 1, rg32ui) uniform uimageBuffer nodeData;

#define FRAG_LOAD(node) imageLoad(nodeData, int(node)).rg
#define FRAG_STORE(node, frag) imageStore(nodeData, int(node), uvec4((frag), 0u, 0u))
// Equal depths are ordered by colour bits (as the CPU reference does), so the result never
// depends on the order fragments were stored in, which on a GPU changes from frame to frame.
#define FRAG_FARTHER(a, b) ((a).y > (b).y || ((a).y == (b).y && (a).x > (b).x))

uvec2 frag_pack(vec4 rgba, float depth) { return uvec2(packUnorm4x8(rgba), floatBitsToUint(depth)); }

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
