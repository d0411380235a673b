// Per-pixel arrays one after the other in one SSBO (Brüll 2018, Eq. 4.1):
//   index(x, y, i) = (y * w + x) * n + i
#include "api.glsl"

layout(std430, binding = STORAGE_BUFFER_BINDING) coherent buffer StorageNodes { uvec2 storageNodes[]; };

int storage_index(ivec2 p, int i) { return (p.y * STORAGE_WIDTH + p.x) * STORAGE_NODES + i; }
uvec2 storage_load(ivec2 p, int i) { return storageNodes[storage_index(p, i)]; }
void storage_store(ivec2 p, int i, uvec2 node) { storageNodes[storage_index(p, i)] = node; }
