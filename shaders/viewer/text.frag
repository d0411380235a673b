// The viewer's overlay text and its backdrop: flat colours, blended over the image.
#include "../common/oitbench.glsl"
in vec4 vColour;
out vec4 colour;
void main() { colour = vColour; }
