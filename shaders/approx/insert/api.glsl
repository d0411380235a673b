// The interface every per-pixel array technique's insertion implements (one file each, like
// shaders/sorts/ against sorts/api.glsl). approx/insert.frag includes exactly one of them under its
// TECH_ define and calls it, under the per-pixel spinlock or the fragment shader interlock, with
//   void insert(ivec2 p, vec4 c, vec4 ct, float z);
// p the pixel, c the shaded fragment colour (straight alpha), ct = (premultiplied colour C, transmittance
// T), z its window depth. A file declares its own register arrays (N + 1 entries: the pixel's nodes and
// the new fragment) and reads and writes the pixel's n nodes through the storage API (STORAGE_LOAD,
// STORAGE_STORE of shaders/storage/) with the encodings of approx/nodes.glsl. Available: N, GUARD(x, lo)
// (the numeric guard APPROX_UNGUARDED removes), DEPTH_EMPTY and the node helpers.
//   mlab.glsl umlab.glsl at.glsl hat.glsl (both through at_family.glsl) uat.glsl uhat.glsl laat.glsl ht.glsl
