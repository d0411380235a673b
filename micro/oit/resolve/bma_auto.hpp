#pragma once
// BMA-AUTO: BMA whose per-interval sort is chosen on the running driver instead of fixed by the
// technique name. At prepare time each candidate sort (IS; IMS where it differs from IS, i.e.
// intervals above 32; RBS-L) resolves each used interval's pixels under its stencil mask: one
// warm-up draw (the JIT) and 5 timed draws, whose median counts (on the run's primary clock: the
// CPU clock around glFinish on software renderers, GL_TIME_ELAPSED on hardware drivers); the fastest candidate whose
// pixels match the CPU reference wins. Choices are cached in a small JSON file keyed on GL_RENDERER, GL_VERSION, the
// interval, the register block size and the order the interval's lists arrive in (sorted ... reverse, 5 classes:
// insertion sort's cost depends on it more than on anything else, so a choice made on sorted lists must not be reused
// on reverse-sorted ones), so the calibration is paid once per driver and input class (it is counted in compile_ms,
// never in the timed passes).
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/registry.hpp"
#include "oit/reference/reference.hpp"
#include "oit/resolve/resolve_sort.hpp"

namespace oitbench::oit {

// $XDG_CACHE_HOME/oitbench/bma_auto.json, else $HOME/.cache/oitbench/bma_auto.json ("" without either).
std::string bma_auto_cache_path();

class SortChoiceCache {
 public:
  explicit SortChoiceCache(std::string path);  // a missing or unreadable file is an empty cache
  static std::string key(const GlInfo& gl, unsigned interval_top, unsigned block, const std::string& order);
  std::optional<SortChoice> find(const std::string& key) const;
  void put(const std::string& key, const SortChoice& sort, const std::map<std::string, double>& timings_ms);
  void save() const;  // creates the folder; a failure to write is ignored (the cache is an optimisation)

 private:
  std::string path_;
  nlohmann::json entries_;
};

struct CandidateResult {
  double median_ms = 0;
  bool valid = false;
};

// The candidates for an interval whose deepest pixel has `interval_top` fragments: IS, and IS with
// the order check; IMS (with and without it) above 32; RBS-L with each block sort (RS and the two
// register networks), and RBS-L with the bitonic network and the order check.
std::vector<SortChoice> bma_auto_candidates(unsigned interval_top);

struct BmaAutoChoice {
  std::vector<std::optional<SortChoice>> sort;  // per interval; empty where the interval has no pixels
  std::string source;                           // calibrated | cached | mixed
  std::string timings;  // "16/reverse:IS=3.1,RBS-L=2.2 ..." (median ms) for the calibrated intervals
};

// The order each interval's lists arrive in, from the fraction f of adjacent fragment pairs already
// far-to-near (what the resolves want): sorted (f >= 0.9), mostly-sorted (>= 0.6), mixed,
// mostly-reverse (<= 0.4), reverse (<= 0.1).
std::vector<std::string> interval_orders(const HostLists& lists, const ListStats& stats,
                                         const std::vector<unsigned>& interval_tops);

// For every interval i with pixels[i] > 0: the cached choice, else the fastest valid candidate
// by `measure(i, sort)` (which runs the warm-up and timed draws). Calibrated choices go into
// `cache` (unless `use_cache` is false: then every interval is calibrated and nothing is stored).
BmaAutoChoice choose_interval_sorts(const std::vector<unsigned>& interval_tops, const std::vector<unsigned>& pixels,
                                    const std::vector<std::string>& orders, const GlInfo& gl, unsigned block,
                                    SortChoiceCache& cache, bool use_cache,
                                    const std::function<CandidateResult(size_t, const SortChoice&)>& measure);

// "8:IS 16:IS 32:RBS-L" for the metric column.
std::string describe_choice(const std::vector<unsigned>& interval_tops, const BmaAutoChoice& choice);

// Whether the resolve output matches the reference on the pixels whose depth is in [lo, hi]
// (pixels with equal-depth ties excepted), i.e. on one BMA interval's pixels only.
bool interval_matches_reference(const std::vector<float>& rgba, const std::vector<double>& reference,
                                const ListStats& stats, unsigned lo, unsigned hi, double tolerance);

}  // namespace oitbench::oit
