// Eq. 4.1's linear SSBO, but read through a buffer texture (texelFetch on a usamplerBuffer over
// the same buffer: the texture path and its cache) and written through the SSBO. The texture
// cache is not coherent with the SSBO writes of the same draw, so a read-modify-write repeated
// within one draw may read stale nodes on hardware: those show up as lost updates.
#include "api.glsl"

layout(std430, binding = STORAGE_BUFFER_BINDING) coherent writeonly buffer StorageNodes { uvec2 storageNodes[]; };
layout(binding = STORAGE_READ_TEXTURE_UNIT) uniform usamplerBuffer storageRead;

int storage_index(ivec2 p, int i) { return (p.y * STORAGE_WIDTH + p.x) * STORAGE_NODES + i; }
uvec2 storage_load(ivec2 p, int i) { return texelFetch(storageRead, storage_index(p, i)).xy; }
void storage_store(ivec2 p, int i, uvec2 node) { storageNodes[storage_index(p, i)] = node; }
