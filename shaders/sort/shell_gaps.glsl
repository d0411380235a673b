// The gap sequence of Brüll 2018 Listing 4.13, shared by shell.glsl and shell_register.glsl.
#ifndef SORT_SHELL_GAPS_GLSL
#define SORT_SHELL_GAPS_GLSL

const int shell_gaps[4] = int[4](20, 9, 4, 1);

int shell_start_gap(int size) { return size > 20 ? 0 : (size > 9 ? 1 : (size > 4 ? 2 : 3)); }

#endif
