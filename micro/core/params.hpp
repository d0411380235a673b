#pragma once
// Experiment parameters: their specs (what `oitbench list` prints and the CLI validates),
// one case's values, and the cartesian product of value lists (like hyperfine's --parameter-list).
#include <functional>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace oitbench {

class UsageError : public std::runtime_error {  // bad command line or preset: exit code 2
 public:
  using std::runtime_error::runtime_error;
};

class ParamSet;

struct ParamSpec {
  enum class Kind { Text, Integer, Number };
  std::string name;
  std::string description;
  std::vector<std::string> defaults;  // the full grid
  std::vector<std::string> quick;     // the --quick grid; empty means the defaults
  std::vector<std::string> allowed;   // enumerated values; empty means any value of `kind` in [min, max]
  Kind kind = Kind::Text;
  double min = -1e300, max = 1e300;
  // Where the parameter means something: every condition must hold (another parameter of the case
  // takes one of the values). Empty: every case. A case it does not apply to runs with its first
  // default and writes the column empty; a --set of it where no case uses it is a usage error.
  struct Condition {
    std::string param;
    std::vector<std::string> values;
  };
  std::vector<Condition> applies_when = {};
  // A condition no parameter list can say (the oit experiment's shadow parameters: the case's scene and
  // effects hold self-shadowing), and its text for messages; unset: none. Scoped like applies_when: a
  // case it does not hold for runs the first default, and such cases are kept once.
  std::function<bool(const ParamSet&)> applies_if = {};
  std::string applies_if_text = {};
  // The parameters applies_if reads: a grid asks it once per combination of their values (empty: it
  // may read any, and is asked for every case).
  std::vector<std::string> applies_if_reads = {};

  // Named constructors, so that a declaration reads as what it is. `defaults` is the full grid,
  // `quick` the --quick grid (empty: the defaults).
  // One of `allowed`; empty defaults: every allowed value.
  static ParamSpec choice(std::string name, std::string description, std::vector<std::string> allowed,
                          std::vector<std::string> defaults = {}, std::vector<std::string> quick = {});
  // An integer in [min, max].
  static ParamSpec integer(std::string name, std::string description, double min, double max,
                           std::vector<std::string> defaults, std::vector<std::string> quick = {});
  // Any text (a scene name or a path): the experiment checks it.
  static ParamSpec text(std::string name, std::string description, std::vector<std::string> defaults,
                        std::vector<std::string> quick = {});

  ParamSpec& only_when(std::string param, std::vector<std::string> values) {
    applies_when.push_back({std::move(param), std::move(values)});
    return *this;
  }
  bool applies(const ParamSet& p) const;
  std::string scope_text() const;  // "technique in {MLAB, AT}"; empty for an unscoped parameter

  // Throws UsageError naming the parameter and listing the valid values.
  void check(const std::string& value, const std::string& experiment) const;
  std::string allowed_text() const;  // "a|b|c" or "integer in [1, 4096]"
  // The bounds check() applies: min and max, within an int's range for an integer without its own.
  double lowest() const;
  double highest() const;
};

// One case: values in the experiment's parameter order.
class ParamSet {
 public:
  ParamSet() = default;
  explicit ParamSet(std::vector<std::pair<std::string, std::string>> values) : values_(std::move(values)) {}
  const std::string& get(const std::string& name) const;  // throws std::out_of_range naming the parameter
  bool has(const std::string& name) const;
  long long get_int(const std::string& name) const;
  double get_double(const std::string& name) const;
  // Every parameter, those that do not apply to this case included (at their defaults).
  const std::vector<std::pair<std::string, std::string>>& values() const { return values_; }
  // Only the parameters this case uses: what its rows record and what tells two cases apart.
  std::vector<std::pair<std::string, std::string>> used_values() const;
  bool uses(const std::string& name) const { return has(name) && !unused_.count(name); }
  void mark_unused(const std::string& name) { unused_.insert(name); }
  std::string describe() const;  // "n=8 stage=compute" (the parameters it uses)
  void set(const std::string& name, const std::string& value);

 private:
  std::vector<std::pair<std::string, std::string>> values_;
  std::set<std::string> unused_;
};

// Integers the command line takes: at most 2^53 in magnitude (exact as doubles too).
inline constexpr long long kMaxExactInteger = 9007199254740992LL;
// Values one --set list may expand to (ranges included).
inline constexpr size_t kMaxRangeValues = 100000;
// A decimal integer ("-12", "+7"), every character used, |value| <= kMaxExactInteger.
bool parse_exact_integer(const std::string& text, long long& out);

// Splits "name=v1,v2,..." (with integer ranges "a..b" and "a..b:step" expanded); throws UsageError.
std::pair<std::string, std::vector<std::string>> parse_set_option(const std::string& text);
// Every --set of a command line, by name; a parameter set twice is a UsageError (it would silently keep
// one of them). `option` names the option in messages.
std::map<std::string, std::vector<std::string>> parse_set_options(const std::vector<std::string>& texts,
                                                                  const std::string& option = "--set");

// The product over the specs: an override list replaces that parameter's defaults (or quick grid).
// A parameter that does not apply to a case (ParamSpec::applies_when) is set to its first default
// and marked unused, and cases that then agree on every used parameter are kept once. Throws
// UsageError when an override applies to no case, or when the grid exceeds `max_cases` (checked before
// it is built). Every case in memory: a run walks its grid instead (core/grid.hpp).
inline constexpr size_t kMaxGridCases = 100000;
std::vector<ParamSet> expand_grid(const std::vector<ParamSpec>& specs,
                                  const std::map<std::string, std::vector<std::string>>& overrides, bool quick,
                                  size_t max_cases = kMaxGridCases);

}  // namespace oitbench
