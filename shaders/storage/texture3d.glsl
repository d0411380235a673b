// A w x h x n 3D texture (RG32UI) through image load/store: the driver's tiled (space-filling)
// layout instead of Eq. 4.1's linear one (Brüll 2018, section 4.1, "Textures").
#include "api.glsl"

layout(rg32ui, binding = STORAGE_IMAGE_UNIT) coherent uniform uimage3D storageImage;

uvec2 storage_load(ivec2 p, int i) { return imageLoad(storageImage, ivec3(p, i)).xy; }
void storage_store(ivec2 p, int i, uvec2 node) { imageStore(storageImage, ivec3(p, i), uvec4(node, 0u, 0u)); }
