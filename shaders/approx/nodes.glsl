// Per-pixel node arrays of the approximate techniques (Brüll 2018, sections 3.6, 3.7, chapters 5
// and 6), kept in the storage include's uvec2 nodes. A cleared node (0, 0) must read as the
// initialisation node, so the encodings are chosen to make all-zero bits mean "empty":
//   depth:  y = floatBitsToUint(z) + 1, 0 = empty (Z = DEPTH_EMPTY); z = gl_FragCoord.z in [0, 1]
//   MLAB:   x = packUnorm4x8(vec4(C, 1 - T)): premultiplied colour, transmittance (3 + 1 bytes);
//           empty = (C 0, T 1), the identity of the merge (the thesis initialises T = 0, which
//           would zero the background term of a pixel with fewer than n fragments)
//   AT:     x = floatBitsToUint(T) ^ floatBitsToUint(1.0): empty = T 1
//   LAAT:   the AT encoding with the low 5 mantissa bits replaced by the link (next slot + 1,
//           0 = end of list); the extra slot STORAGE_NODES - 1 holds the head (first slot + 1)
// The same encodings are mirrored on the CPU in micro/oit/approx/approx_model.cpp (the techniques' own models).
#ifndef APPROX_NODES_GLSL
#define APPROX_NODES_GLSL

#define N STORAGE_NODES
const float DEPTH_EMPTY = 3.4028235e38;
const uint ONE_BITS = 0x3F800000u;

float node_depth(uvec2 node) { return node.y == 0u ? DEPTH_EMPTY : uintBitsToFloat(node.y - 1u); }
uint encode_depth(float z) { return z >= DEPTH_EMPTY ? 0u : floatBitsToUint(z) + 1u; }

vec4 mlab_value(uvec2 node) {  // (C, T)
  vec4 k = unpackUnorm4x8(node.x);
  return vec4(k.rgb, 1.0 - k.a);
}
uvec2 mlab_node(vec4 ct, float z) { return uvec2(packUnorm4x8(vec4(ct.rgb, 1.0 - ct.a)), encode_depth(z)); }

#if defined(TECH_LAAT)
float at_transmittance(uvec2 node) { return uintBitsToFloat((node.x & ~31u) ^ ONE_BITS); }
#else
float at_transmittance(uvec2 node) { return uintBitsToFloat(node.x ^ ONE_BITS); }
#endif
uvec2 at_node(float t, float z) { return uvec2(floatBitsToUint(t) ^ ONE_BITS, encode_depth(z)); }

// HT_HTGS (HT's ht_variant=htgs, HTGS's HYBRID_BLEND): only fragments of this alpha or more enter the core.
const float HTGS_CORE_ALPHA = 0.05;

#endif
