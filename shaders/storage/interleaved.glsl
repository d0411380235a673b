// Interleaved SSBO (Brüll 2018, Eq. 4.2): pixels are packed into gx x gy groups and node i of all
// pixels of a group lie next to each other, so a warp's 2x2..8x8 block touches few memory chunks.
// STORAGE_ALIGN > 1 generalises Eq. 4.2: a pixel's nodes are kept in runs of STORAGE_ALIGN
// consecutive nodes (4 nodes x 8 bytes = the 32-byte chunks the thesis aligns to); with
// STORAGE_ALIGN 1 this is exactly Eq. 4.2. The row of groups is rounded up when w % gx != 0.
#include "api.glsl"

#if !defined(STORAGE_GROUP_X) || !defined(STORAGE_GROUP_Y) || !defined(STORAGE_ALIGN)
#error "the interleaved layout needs STORAGE_GROUP_X, STORAGE_GROUP_Y and STORAGE_ALIGN"
#endif
#if (STORAGE_NODES % STORAGE_ALIGN) != 0
#error "STORAGE_NODES must be a multiple of STORAGE_ALIGN"
#endif

layout(std430, binding = STORAGE_BUFFER_BINDING) coherent buffer StorageNodes { uvec2 storageNodes[]; };

const int storageGroupsPerRow = (STORAGE_WIDTH + STORAGE_GROUP_X - 1) / STORAGE_GROUP_X;
const int storageStride = STORAGE_GROUP_X * STORAGE_GROUP_Y;  // pixels per group

int storage_index(ivec2 p, int i) {
  int gID = (p.y / STORAGE_GROUP_Y) * storageGroupsPerRow + p.x / STORAGE_GROUP_X;
  int gOffset = gID * STORAGE_NODES * storageStride;
  int localID = (p.y % STORAGE_GROUP_Y) * STORAGE_GROUP_X + p.x % STORAGE_GROUP_X;
  int run = i / STORAGE_ALIGN;
  return gOffset + (run * storageStride + localID) * STORAGE_ALIGN + i % STORAGE_ALIGN;
}
uvec2 storage_load(ivec2 p, int i) { return storageNodes[storage_index(p, i)]; }
void storage_store(ivec2 p, int i, uvec2 node) { storageNodes[storage_index(p, i)] = node; }
