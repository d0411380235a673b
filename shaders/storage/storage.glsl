// Picks the storage include named by the injected define; see api.glsl for the API.
#ifndef OITBENCH_STORAGE_GLSL
#define OITBENCH_STORAGE_GLSL

// Included here, outside the #if chain: the shader assembler inlines each file once wherever it
// is first named, whatever the preprocessor later keeps.
#include "api.glsl"

#if defined(STORAGE_SSBO)
#include "ssbo.glsl"
#elif defined(STORAGE_TEXTURE3D)
#include "texture3d.glsl"
#elif defined(STORAGE_INTERLEAVED)
#include "interleaved.glsl"
#elif defined(STORAGE_TEXBUFFER)
#include "texbuffer.glsl"
#else
#error "define one of STORAGE_SSBO, STORAGE_TEXTURE3D, STORAGE_INTERLEAVED, STORAGE_TEXBUFFER"
#endif

#endif
