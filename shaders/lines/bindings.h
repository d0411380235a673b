// Binding points of the stream-split radix sort of primitives (slice_keys.comp, split.comp,
// emit_indices.comp), shared by the lines experiment (micro/experiments/lines.cpp) and the
// self-shadowing map (micro/oit/scene/shadow_map.cpp). Each pass is its own dispatch, so the
// passes reuse the same storage-buffer points. Only #defines: valid C++ and GLSL.
#ifndef OITBENCH_LINES_BINDINGS_H
#define OITBENCH_LINES_BINDINGS_H

// slice_keys.comp: each primitive's depth-slice key
#define SLICE_KEYS_VERTICES_BINDING 0    // SSBO: the scene mesh's oit::Vertex records, read as floats
#define SLICE_KEYS_KEYS_BINDING 1        // SSBO: out, one key per primitive
#define SLICE_KEYS_INDICES_BINDING 2     // SSBO: out, the identity order 0..n-1
#define SLICE_KEYS_PRIMITIVES_BINDING 3  // SSBO: the primitives' vertex indices

// split.comp: one bit of the radix sort per round
#define SPLIT_KEYS_IN_BINDING 0      // SSBO: this round's keys
#define SPLIT_INDICES_IN_BINDING 1   // SSBO: this round's primitive order
#define SPLIT_KEYS_OUT_BINDING 2     // SSBO: out, the keys split on the bit
#define SPLIT_INDICES_OUT_BINDING 3  // SSBO: out, the order split on the bit
#define SPLIT_LOCAL_BINDING 4        // SSBO: each key's prefix count within its block
#define SPLIT_BLOCKS_BINDING 5       // SSBO: [0] total zeros, [1 + b] block b's prefix

// emit_indices.comp: the sorted order as an element buffer
#define EMIT_SORTED_BINDING 0      // SSBO: the sorted primitive order
#define EMIT_ELEMENTS_BINDING 1    // SSBO: out, the element buffer
#define EMIT_PRIMITIVES_BINDING 2  // SSBO: the primitives' vertex indices

#endif
