// WOIT's setup probe: a constant added by the blender to a half-float target, to learn how the driver
// rounds the sum (wavelet_case.cpp, blend_half_rounding).
#include "../common/oitbench.glsl"
uniform float addend;
layout(location = 0) out vec4 probe;
void main() { probe = vec4(addend); }
