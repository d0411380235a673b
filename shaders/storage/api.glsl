// The per-pixel node storage API every storage include implements, so that a technique is
// written once and its storage is one injected define (STORAGE_SSBO, STORAGE_TEXTURE3D,
// STORAGE_INTERLEAVED, STORAGE_TEXBUFFER; see storage.glsl).
//
// Before including, define (the C++ side injects them: micro/oit/storage/storage_layout.hpp):
//   STORAGE_WIDTH, STORAGE_HEIGHT  the screen in pixels
//   STORAGE_NODES                  nodes per pixel (n)
//   STORAGE_GROUP_X, STORAGE_GROUP_Y, STORAGE_ALIGN   interleaved only (Eq. 4.2 and its alignment)
//
// Provides:
//   STORAGE_NODE                      the node type: uvec2 (8 bytes, like an AT/MLAB node)
//   STORAGE_LOAD(pixel, i)            node i of the pixel (ivec2)
//   STORAGE_STORE(pixel, i, node)     writes node i of the pixel
// Nodes are not atomic: concurrent read-modify-writes of one pixel need a lock or interlock.
#ifndef OITBENCH_STORAGE_API_GLSL
#define OITBENCH_STORAGE_API_GLSL

#include "bindings.h"

#define STORAGE_NODE uvec2
#define STORAGE_LOAD(pixel, i) storage_load(pixel, i)
#define STORAGE_STORE(pixel, i, node) storage_store(pixel, i, node)

#if !defined(STORAGE_WIDTH) || !defined(STORAGE_HEIGHT) || !defined(STORAGE_NODES)
#error "define STORAGE_WIDTH, STORAGE_HEIGHT and STORAGE_NODES before including a storage layout"
#endif

#endif
