#pragma once
// Experiment parameters: their specs (what `oitbench list` prints and the CLI validates),
// one case's values, and the cartesian product of value lists (like hyperfine's --parameter-list).
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace oitbench {

class UsageError : public std::runtime_error {  // bad command line or preset: exit code 2
 public:
  using std::runtime_error::runtime_error;
};

struct ParamSpec {
  enum class Kind { Text, Integer, Number };
  std::string name;
  std::string description;
  std::vector<std::string> defaults;  // the full grid
  std::vector<std::string> quick;     // the --quick grid; empty means the defaults
  std::vector<std::string> allowed;   // enumerated values; empty means any value of `kind` in [min, max]
  Kind kind = Kind::Text;
  double min = -1e300, max = 1e300;

  // Throws UsageError naming the parameter and listing the valid values.
  void check(const std::string& value, const std::string& experiment) const;
  std::string allowed_text() const;  // "a|b|c" or "integer in [1, 4096]"
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
  const std::vector<std::pair<std::string, std::string>>& values() const { return values_; }
  std::string describe() const;  // "n=8 stage=compute"
  void set(const std::string& name, const std::string& value);

 private:
  std::vector<std::pair<std::string, std::string>> values_;
};

// Splits "name=v1,v2,..." (with integer ranges "a..b" and "a..b:step" expanded); throws UsageError.
std::pair<std::string, std::vector<std::string>> parse_set_option(const std::string& text);

// The product over the specs: an override list replaces that parameter's defaults (or quick grid).
std::vector<ParamSet> expand_grid(const std::vector<ParamSpec>& specs,
                                  const std::map<std::string, std::vector<std::string>>& overrides, bool quick);

}  // namespace oitbench
