// Binding points of the per-pixel node storage, shared by the C++ side and every storage include
// (only #defines and comments, so it is valid C++ and GLSL).
#ifndef OITBENCH_STORAGE_BINDINGS_H
#define OITBENCH_STORAGE_BINDINGS_H

#define STORAGE_BUFFER_BINDING 0     // SSBO of the ssbo, interleaved and texbuffer layouts
#define STORAGE_IMAGE_UNIT 0         // uimage3D of the texture3d layout
#define STORAGE_READ_TEXTURE_UNIT 0  // usamplerBuffer through which the texbuffer layout reads

#endif
