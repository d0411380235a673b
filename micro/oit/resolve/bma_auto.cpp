#include "oit/resolve/bma_auto.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace oitbench::oit {

std::string bma_auto_cache_path() {
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  if (xdg && *xdg) return (std::filesystem::path(xdg) / "oitbench" / "bma_auto.json").string();
  const char* home = std::getenv("HOME");
  if (home && *home) return (std::filesystem::path(home) / ".cache" / "oitbench" / "bma_auto.json").string();
  return "";
}

SortChoiceCache::SortChoiceCache(std::string path) : path_(std::move(path)), entries_(nlohmann::json::object()) {
  if (path_.empty()) return;
  std::ifstream in(path_);
  if (!in) return;
  try {
    auto j = nlohmann::json::parse(in);
    if (j.is_object()) entries_ = std::move(j);
  } catch (const nlohmann::json::exception&) {
    // A corrupt cache is recalibrated and rewritten.
  }
}

std::string SortChoiceCache::key(const GlInfo& gl, unsigned interval_top, unsigned block, const std::string& order) {
  return gl.renderer + " | " + gl.version + " | interval " + std::to_string(interval_top) + " | block " +
         std::to_string(block) + " | " + order + " | candidates 3";  // 3: with RBS-L/bitonic+order-check
}

std::vector<std::string> interval_orders(const HostLists& lists, const ListStats& stats,
                                         const std::vector<unsigned>& interval_tops) {
  std::vector<size_t> in_order(interval_tops.size(), 0), pairs(interval_tops.size(), 0);
  for (size_t p = 0; p < lists.heads.size() && p < stats.depth.size(); ++p) {
    unsigned d = stats.depth[p];
    if (d < 2) continue;
    size_t i = 0;
    while (i + 1 < interval_tops.size() && d > interval_tops[i]) ++i;
    unsigned node = lists.heads[p];
    for (unsigned k = 0; k + 1 < d && node < lists.nodes.size(); ++k) {
      unsigned next = lists.next[node];
      if (next >= lists.nodes.size()) break;
      in_order[i] += lists.nodes[node].y >= lists.nodes[next].y;  // far-to-near: descending depth
      ++pairs[i];
      node = next;
    }
  }
  std::vector<std::string> out(interval_tops.size(), "mixed");
  for (size_t i = 0; i < out.size(); ++i) {
    if (!pairs[i]) continue;
    double f = static_cast<double>(in_order[i]) / static_cast<double>(pairs[i]);
    out[i] = f >= 0.9   ? "sorted"
             : f >= 0.6 ? "mostly-sorted"
             : f > 0.4  ? "mixed"
             : f > 0.1  ? "mostly-reverse"
                        : "reverse";
  }
  return out;
}

std::optional<SortChoice> SortChoiceCache::find(const std::string& key) const {
  auto it = entries_.find(key);
  if (it == entries_.end() || !it->is_object() || !it->contains("sort") || !(*it)["sort"].is_string())
    return std::nullopt;
  try {
    return parse_choice_label((*it)["sort"].get<std::string>());
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  }
}

void SortChoiceCache::put(const std::string& key, const SortChoice& sort,
                          const std::map<std::string, double>& timings_ms) {
  entries_[key] = {{"sort", choice_label(sort)}, {"median_ms", timings_ms}};
}

void SortChoiceCache::save() const {
  if (path_.empty()) return;
  std::error_code ec;
  std::filesystem::create_directories(std::filesystem::path(path_).parent_path(), ec);
  // Write then rename, so a concurrent reader never sees half a file.
  std::string tmp = path_ + ".tmp" + std::to_string(::getpid());
  {
    std::ofstream out(tmp);
    if (!out) return;
    out << entries_.dump(2) << "\n";
  }
  std::filesystem::rename(tmp, path_, ec);
  if (ec) std::filesystem::remove(tmp, ec);
}

std::vector<SortChoice> bma_auto_candidates(unsigned interval_top) {
  std::vector<SortChoice> c = {{ResolveSort::IS}, {ResolveSort::IS, BlockSort::Insertion, true}};
  // IMS sorts by insertion up to 32 fragments: below that it is IS under another name.
  if (interval_top > 32) {
    c.push_back({ResolveSort::IMS});
    c.push_back({ResolveSort::IMS, BlockSort::Insertion, true});
  }
  for (BlockSort b : {BlockSort::Insertion, BlockSort::Bitonic, BlockSort::OddEvenMerge})
    c.push_back({ResolveSort::RBS_L, b});
  // The network with the order check: a sorted list skips the network and the merge, a reversed one
  // is reversed in O(n) (unchecked, the networks sort sorted input all the same).
  c.push_back({ResolveSort::RBS_L, BlockSort::Bitonic, true});
  return c;
}

BmaAutoChoice choose_interval_sorts(const std::vector<unsigned>& interval_tops, const std::vector<unsigned>& pixels,
                                    const std::vector<std::string>& orders, const GlInfo& gl, unsigned block,
                                    SortChoiceCache& cache, bool use_cache,
                                    const std::function<CandidateResult(size_t, const SortChoice&)>& measure) {
  BmaAutoChoice choice;
  choice.sort.resize(interval_tops.size());
  bool any_cached = false, any_calibrated = false, dirty = false;
  std::ostringstream timings;
  for (size_t i = 0; i < interval_tops.size(); ++i) {
    if (i >= pixels.size() || !pixels[i]) continue;
    std::string key = SortChoiceCache::key(gl, interval_tops[i], block, i < orders.size() ? orders[i] : "mixed");
    if (auto hit = use_cache ? cache.find(key) : std::nullopt) {
      choice.sort[i] = *hit;
      any_cached = true;
      continue;
    }
    any_calibrated = true;
    std::map<std::string, double> ms;
    std::optional<SortChoice> best;
    double best_ms = INFINITY;
    timings << (timings.tellp() > 0 ? " " : "") << interval_tops[i] << "/" << (i < orders.size() ? orders[i] : "mixed")
            << ":";
    bool first = true;
    for (const SortChoice& s : bma_auto_candidates(interval_tops[i])) {
      CandidateResult r = measure(i, s);
      timings << (first ? "" : ",") << choice_label(s) << "=" << (r.valid ? "" : "invalid/") << r.median_ms;
      first = false;
      if (!r.valid) continue;
      ms[choice_label(s)] = r.median_ms;
      if (r.median_ms < best_ms) {
        best_ms = r.median_ms;
        best = s;
      }
    }
    // No valid candidate: fall back to IS (the run is then validated, and fails, like any other).
    choice.sort[i] = best.value_or(SortChoice{ResolveSort::IS});
    if (best) {
      cache.put(key, *best, ms);
      dirty = true;
    }
  }
  if (dirty && use_cache) cache.save();
  choice.source = any_cached && any_calibrated ? "mixed" : any_cached ? "cached" : "calibrated";
  choice.timings = timings.str();
  return choice;
}

std::string describe_choice(const std::vector<unsigned>& interval_tops, const BmaAutoChoice& choice) {
  std::string s;
  for (size_t i = 0; i < interval_tops.size() && i < choice.sort.size(); ++i)
    if (choice.sort[i])
      s += (s.empty() ? "" : " ") + std::to_string(interval_tops[i]) + ":" + choice_label(*choice.sort[i]);
  return s;
}

bool interval_matches_reference(const std::vector<float>& rgba, const std::vector<double>& reference,
                                const ListStats& stats, unsigned lo, unsigned hi, double tolerance) {
  for (size_t p = 0; p < stats.depth.size(); ++p) {
    unsigned d = stats.depth[p];
    if (d < lo || d > hi || (p < stats.tied.size() && stats.tied[p])) continue;
    if (std::abs(rgba[4 * p + 3] - 1.0f) > 1e-3f) return false;  // resolved exactly once
    for (int c = 0; c < 3; ++c)
      if (std::abs(rgba[4 * p + c] - reference[3 * p + c]) > tolerance) return false;
  }
  return true;
}

}  // namespace oitbench::oit
