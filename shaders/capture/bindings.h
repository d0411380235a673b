// Binding points of the captured fragments' storage (fragment_storage.glsl and its two layouts,
// fragment_lists.glsl and packed_arrays.glsl) and of the prefix sum that sizes the packed arrays.
// Only #defines: valid C++ (micro/oit/capture/) and GLSL. The resolves and sorts that read the
// fragments bind nothing of their own below these.
#ifndef OITBENCH_CAPTURE_BINDINGS_H
#define OITBENCH_CAPTURE_BINDINGS_H

#define CAPTURE_HEADS_UNIT 0       // image, PPLL: each pixel's first node
#define CAPTURE_NODES_UNIT 1       // image (texel buffer): the fragments, both layouts
#define CAPTURE_NEXT_UNIT 2        // image (texel buffer), PPLL: next pointers
#define CAPTURE_COUNTS_UNIT 3      // image: fragments per pixel (PPPA; PPLL with STORAGE_COUNTS)
#define CAPTURE_NODE_DEPTH_UNIT 5  // image (texel buffer): the depths of the wide colour formats
#define CAPTURE_CHUNK_UNIT_BASE 8  // images 8..: chunks 1.. of each array past one texel buffer's limit
#define CAPTURE_COUNTER_BINDING 0  // atomic counter, PPLL: nodes allocated
#define CAPTURE_OFFSETS_BINDING 2  // SSBO, PPPA: each pixel's first node (the prefix sum's output)

#define SCAN_IN_BINDING 0                     // SSBO: the prefix sum's input level
#define SCAN_OUT_BINDING 1                    // SSBO: its output level
#define SCAN_BLOCK_SUMS_BINDING 2             // SSBO: the block sums carried to the next level
#define SCAN_COUNTS_UNIT CAPTURE_COUNTS_UNIT  // image: the counts the first level reads

#endif
