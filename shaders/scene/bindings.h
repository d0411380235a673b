// Texture units of the scene effects' resources (micro/oit/scene/scene_passes.cpp binds them), read by
// every technique's shaders through shaders/scene/backdrop.glsl. Only #defines: valid C++ and GLSL.
#ifndef OITBENCH_SCENE_BINDINGS_H
#define OITBENCH_SCENE_BINDINGS_H
#define OIT_BACKDROP_UNIT 7      // sampler2D, RGBA32F: the opaque pass's colour (opaque effect)
#define OIT_OPAQUE_DEPTH_UNIT 9  // sampler2D: the opaque pass's depth, for techniques without a depth buffer
#endif
