// Every sort, one file each; the entry points call the one named by the injected SORT_ALGORITHM
// (e.g. sort_insertion_v2). Adding a sort: write shaders/sort/<name>.glsl against frags.glsl's API,
// include it here and list it in micro/experiments/sort.cpp.
#include "insertion_naive.glsl"
#include "insertion_v1.glsl"
#include "insertion_v2.glsl"
#include "bubble.glsl"
#include "shell.glsl"
#include "shell_register.glsl"
#include "merge.glsl"
#include "bitonic.glsl"
#include "odd_even_merge.glsl"
#include "rbs.glsl"
