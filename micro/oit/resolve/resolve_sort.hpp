#pragma once
// Which sort an exact-OIT resolve runs (shaders/resolve/resolve_pixel.glsl), from the technique's
// suffix (BASE-IS, CS-RBS-L, RBS-G, ...), the defines that select and size it, and the files of
// the sort library (shaders/sorts/) it compiles.
#include <string>
#include <vector>

#include "gl/shader.hpp"

namespace oitbench::oit {

enum class ResolveSort { IS, IMS, RBS_L, RBS_G };

// How RBS sorts each register block (the `block_sort` parameter): RS, the insertion network of
// Knowles 2014 Listing 5 (sorts/register_sort.glsl), or a branchless register network
// (sorts/network.glsl, SORT_NETWORK_BITONIC / SORT_NETWORK_ODD_EVEN_MERGE).
enum class BlockSort { Insertion, Bitonic, OddEvenMerge };
const std::vector<std::string>& block_sort_names();   // "insertion", "bitonic", "odd-even-merge"
BlockSort parse_block_sort(const std::string& name);  // throws std::invalid_argument naming the valid ones

// One resolve sort in full: the sort, RBS's block sort, and whether the resolve checks the order
// of each pixel's list while loading it (IS, IMS, RBS-L: the `order_check` parameter; a list already
// far-to-near skips the sort, one near-to-far is reversed in O(n); RBS-L also skips its merge).
struct SortChoice {
  ResolveSort sort = ResolveSort::IS;
  BlockSort block = BlockSort::Insertion;
  bool order_check = false;
  bool operator==(const SortChoice&) const = default;
};
// "IS", "IS+order-check", "RBS-L", "RBS-L/bitonic", "RBS-G/odd-even-merge", ...
std::string choice_label(const SortChoice& choice);
SortChoice parse_choice_label(const std::string& label);  // the inverse; throws std::invalid_argument

std::string sort_label(ResolveSort sort);                // "IS", "IMS", "RBS-L", "RBS-G"
ResolveSort parse_sort_label(const std::string& label);  // the inverse; throws std::invalid_argument
// MAX_FRAGS plus SORT_IS | SORT_IMS (SORT_MERGE_HALF_SCRATCH) | SORT_RBS (RBS_M, MAX_K) |
// SORT_RBS_G (RBS_M, MAX_K); the register block is min(block, max_frags). A network block sort adds
// SORT_NETWORK_BITONIC or SORT_NETWORK_ODD_EVEN_MERGE, and SORT_PACKED_KEY64 when `packed_key64`
// (the caller knows the fragment format packs into a 64-bit key and the driver has int64); an
// order check adds SORT_ORDER_CHECK (IS, IMS and RBS-L; not RBS-G).
Defines sort_defines(ResolveSort sort, unsigned max_frags, unsigned block);
Defines sort_defines(const SortChoice& choice, unsigned max_frags, unsigned block, bool packed_key64);
// The library files (relative to the shader root) a resolve with these defines compiles, in the
// order it runs them, as resolve_pixel.glsl includes them: IS sorts/insertion.glsl; IMS that and,
// above 32 fragments, sorts/merge.glsl; RBS-L and RBS-G sorts/register_sort.glsl, or
// sorts/network.glsl with a network block sort.
std::vector<std::string> sort_files(ResolveSort sort, unsigned max_frags, BlockSort block = BlockSort::Insertion);

}  // namespace oitbench::oit
