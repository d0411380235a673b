#include "oit/resolve/resolve_sort.hpp"

#include <algorithm>
#include <stdexcept>

namespace oitbench::oit {

std::string sort_label(ResolveSort sort) {
  switch (sort) {
    case ResolveSort::IS:
      return "IS";
    case ResolveSort::IMS:
      return "IMS";
    case ResolveSort::RBS_L:
      return "RBS-L";
    case ResolveSort::RBS_G:
      return "RBS-G";
  }
  return "?";
}

ResolveSort parse_sort_label(const std::string& label) {
  std::string valid;
  for (auto s : {ResolveSort::IS, ResolveSort::IMS, ResolveSort::RBS_L, ResolveSort::RBS_G}) {
    if (sort_label(s) == label) return s;
    valid += (valid.empty() ? "" : ", ") + sort_label(s);
  }
  throw std::invalid_argument("unknown resolve sort '" + label + "' (" + valid + ")");
}

const std::vector<std::string>& block_sort_names() {
  static const std::vector<std::string> names = {"insertion", "bitonic", "odd-even-merge"};
  return names;
}

BlockSort parse_block_sort(const std::string& name) {
  if (name == "insertion") return BlockSort::Insertion;
  if (name == "bitonic") return BlockSort::Bitonic;
  if (name == "odd-even-merge") return BlockSort::OddEvenMerge;
  throw std::invalid_argument("unknown block sort '" + name + "' (insertion, bitonic, odd-even-merge)");
}

std::string choice_label(const SortChoice& c) {
  std::string s = sort_label(c.sort);
  if (c.block != BlockSort::Insertion) s += "/" + block_sort_names()[static_cast<size_t>(c.block)];
  if (c.order_check) s += "+order-check";
  return s;
}

SortChoice parse_choice_label(const std::string& label) {
  SortChoice c;
  std::string rest = label;
  if (rest.ends_with("+order-check")) {
    c.order_check = true;
    rest.resize(rest.size() - std::string("+order-check").size());
  }
  if (auto slash = rest.find('/'); slash != std::string::npos) {
    c.block = parse_block_sort(rest.substr(slash + 1));
    rest.resize(slash);
  }
  c.sort = parse_sort_label(rest);
  return c;
}

Defines sort_defines(const SortChoice& c, unsigned max_frags, unsigned block, bool packed_key64) {
  Defines d = sort_defines(c.sort, max_frags, block);
  bool rbs = c.sort == ResolveSort::RBS_L || c.sort == ResolveSort::RBS_G;
  if (rbs && c.block != BlockSort::Insertion) {
    d.push_back({c.block == BlockSort::Bitonic ? "SORT_NETWORK_BITONIC" : "SORT_NETWORK_ODD_EVEN_MERGE", ""});
    if (packed_key64) d.push_back({"SORT_PACKED_KEY64", ""});
  }
  if (c.order_check && c.sort != ResolveSort::RBS_G) d.push_back({"SORT_ORDER_CHECK", ""});
  return d;
}

Defines sort_defines(ResolveSort sort, unsigned max_frags, unsigned block) {
  Defines d = {{"MAX_FRAGS", std::to_string(max_frags)}};
  if (sort == ResolveSort::IS) {
    d.push_back({"SORT_IS", ""});
  } else if (sort == ResolveSort::IMS) {
    d.push_back({"SORT_IMS", ""});
    d.push_back({"SORT_MERGE_HALF_SCRATCH", ""});  // Knowles 2013's merge (shaders/sorts/merge.glsl)
  } else {
    unsigned m = std::min(block, max_frags);
    d.push_back({sort == ResolveSort::RBS_L ? "SORT_RBS" : "SORT_RBS_G", ""});
    d.push_back({"RBS_M", std::to_string(m)});
    d.push_back({"MAX_K", std::to_string((max_frags + m - 1) / m)});
  }
  return d;
}

std::vector<std::string> sort_files(ResolveSort sort, unsigned max_frags, BlockSort block) {
  switch (sort) {
    case ResolveSort::IS:
      return {"sorts/insertion.glsl"};
    case ResolveSort::IMS:
      if (max_frags > 32) return {"sorts/insertion.glsl", "sorts/merge.glsl"};
      return {"sorts/insertion.glsl"};
    case ResolveSort::RBS_L:
    case ResolveSort::RBS_G:
      if (block != BlockSort::Insertion) return {"sorts/network.glsl", "sorts/network_tables.glsl"};
      return {"sorts/register_sort.glsl"};
  }
  return {};
}

}  // namespace oitbench::oit
