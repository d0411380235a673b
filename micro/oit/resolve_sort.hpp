#pragma once
// Which sort an exact-OIT resolve runs (shaders/oit/resolve_pixel.glsl), from the technique's
// suffix (BASE-IS, CS-RBS-L, RBS-G, ...), the defines that select and size it, and the files of
// the sort library (shaders/sorts/) it compiles.
#include <string>
#include <vector>

#include "gl/shader.hpp"

namespace oitbench::oit {

enum class ResolveSort { IS, IMS, RBS_L, RBS_G };

// "BASE-IMS" -> IMS, "CS-RBS-L" -> RBS_L, "RBS-G" -> RBS_G; throws std::invalid_argument otherwise.
ResolveSort sort_of_technique(const std::string& technique);
std::string sort_label(ResolveSort sort);                // "IS", "IMS", "RBS-L", "RBS-G"
ResolveSort parse_sort_label(const std::string& label);  // the inverse; throws std::invalid_argument
// MAX_FRAGS plus SORT_IS | SORT_IMS (SORT_MERGE_HALF_SCRATCH) | SORT_RBS (RBS_M, MAX_K) |
// SORT_RBS_G (RBS_M, MAX_K); the register block is min(block, max_frags).
Defines sort_defines(ResolveSort sort, unsigned max_frags, unsigned block);
// The library files (relative to the shader root) a resolve with these defines compiles, in the
// order it runs them, as resolve_pixel.glsl includes them: IS sorts/insertion.glsl; IMS that and,
// above 32 fragments, sorts/merge.glsl; RBS-L and RBS-G sorts/register_sort.glsl.
std::vector<std::string> sort_files(ResolveSort sort, unsigned max_frags);

}  // namespace oitbench::oit
