// Every sort, one file each. The case injects SORT_USE_<NAME>; only that file is compiled, so
// compile_ms is the chosen sort's own (the unrolled networks are costly to parse). Each file defines
// its sort function and names it SORT_ALGORITHM. Adding a sort: write shaders/sort/<name>.glsl
// against frags.glsl's API, add it here and to the table in micro/experiments/sort.cpp.
//
// Shared includes come first and unconditionally: the assembler emits a file once, where it is
// first included, so a dependency first met inside a skipped #if block would be lost.
#include "frags.glsl"
#include "unroll.glsl"
#include "shell_gaps.glsl"

#if defined(SORT_USE_INSERTION_NAIVE)
#include "insertion_naive.glsl"
#endif
#if defined(SORT_USE_INSERTION_V1)
#include "insertion_v1.glsl"
#endif
#if defined(SORT_USE_INSERTION_V2)
#include "insertion_v2.glsl"
#endif
#if defined(SORT_USE_BUBBLE)
#include "bubble.glsl"
#endif
#if defined(SORT_USE_SHELL)
#include "shell.glsl"
#endif
#if defined(SORT_USE_SHELL_REGISTER)
#include "shell_register.glsl"
#endif
#if defined(SORT_USE_MERGE)
#include "merge.glsl"
#endif
#if defined(SORT_USE_BITONIC)
#include "bitonic.glsl"
#endif
#if defined(SORT_USE_ODD_EVEN_MERGE)
#include "odd_even_merge.glsl"
#endif
#if defined(SORT_USE_RBS)
#include "rbs.glsl"
#endif
