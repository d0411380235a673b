// The sort experiment's choice of sort: the case injects SORT_USE_<FILE> (and the file's variant
// defines, see the variant table in micro/experiments/sort.cpp); only that library file of
// shaders/sorts/ is compiled, so compile_ms is the chosen sort's own (the unrolled networks are
// costly to parse). SORT_ALGORITHM() is the call that sorts the pixel's frags.glsl array.
// Adding a sort: write shaders/sorts/<name>.glsl against shaders/sorts/api.glsl, add it here and
// to the table in micro/experiments/sort.cpp (which names the same file for `sort_source`).
//
// Shared includes come first and unconditionally: the assembler emits a file once, where it is
// first included, so a dependency first met inside a skipped #if block would be lost.
#include "frags.glsl"
#include "../sorts/api.glsl"
#include "../sorts/unroll.glsl"

#if defined(SORT_USE_INSERTION)
#include "../sorts/insertion.glsl"
#define SORT_ALGORITHM() sort_insertion()
#endif
#if defined(SORT_USE_BUBBLE)
#include "../sorts/bubble.glsl"
#define SORT_ALGORITHM() sort_bubble()
#endif
#if defined(SORT_USE_SHELL)
#include "../sorts/shell.glsl"
#define SORT_ALGORITHM() sort_shell()
#endif
#if defined(SORT_USE_MERGE)
#include "../sorts/merge.glsl"
#define SORT_ALGORITHM() sort_merge()
#endif
#if defined(SORT_USE_BITONIC)
#include "../sorts/bitonic.glsl"
#define SORT_ALGORITHM() sort_bitonic()
#endif
#if defined(SORT_USE_ODD_EVEN_MERGE)
#include "../sorts/odd_even_merge.glsl"
#define SORT_ALGORITHM() sort_odd_even_merge()
#endif
#if defined(SORT_USE_NETWORK)
// The register networks (SORT_NETWORK_BITONIC or SORT_NETWORK_ODD_EVEN_MERGE): SORT_N elements,
// compare-exchanges as min/max of the packed key (frags.glsl, SORT_PACKED_KEY64) or selects.
#include "../sorts/network.glsl"
#define SORT_ALGORITHM() sort_network()
#endif
#if defined(SORT_USE_REGISTER_SORT)
// RS shrinks its network to the `count` uniform (== SORT_N), as a resolve does to a block's fragments.
#include "../sorts/register_sort.glsl"
#define SORT_ALGORITHM() sort_register(count)
#endif
