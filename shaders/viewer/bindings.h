// Binding points of the viewer's shaders (micro/viewer/image_presenter.cpp, depth_complexity.cpp).
// The depth-complexity pass binds beside the fragment storage's own points (shaders/capture/bindings.h:
// images 0-3 and 5, atomic counter 0, storage buffer 2). Only #defines: valid C++ and GLSL.
#ifndef OITBENCH_VIEWER_BINDINGS_H
#define OITBENCH_VIEWER_BINDINGS_H

#define PRESENT_IMAGE_UNIT 0   // texture unit (present.frag): the case's result
#define PRESENT_OPAQUE_UNIT 1  // texture unit (present.frag): the opaque pass's colour, with the opaque effect
#define DEPTH_COUNTS_UNIT 4    // image unit, r32ui: fragments per pixel
#define DEPTH_STATS_BINDING 1  // SSBO: the peak and the total

#endif
