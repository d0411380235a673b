// libFuzzer harness: the --set parser (lists, integer ranges A..B:STEP), the duplicate check and a
// parameter's value check. Any input must end in values or a UsageError, bounded in memory and time.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/params.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  // One or two options, split at the first newline: "size=1..4\nsize=2" tests the duplicate rule.
  std::vector<std::string> options;
  auto nl = text.find('\n');
  options.push_back(text.substr(0, nl));
  if (nl != std::string::npos) options.push_back(text.substr(nl + 1));
  const oitbench::ParamSpec integer{"n", "", {"1"}, {}, {}, oitbench::ParamSpec::Kind::Integer, 0, 4294967295.0};
  const oitbench::ParamSpec unbounded{"m", "", {"1"}, {}, {}, oitbench::ParamSpec::Kind::Integer};
  const oitbench::ParamSpec number{"x", "", {"1"}, {}, {}, oitbench::ParamSpec::Kind::Number, 0, 1};
  try {
    auto sets = oitbench::parse_set_options(options);
    size_t total = 0;
    for (const auto& [name, values] : sets) {
      total += values.size();
      if (values.size() > oitbench::kMaxRangeValues) __builtin_trap();  // the bound the parser promises
      // As check_requests does: every value in turn, the first bad one ends the check (one exception).
      for (const auto* spec : {&integer, &unbounded, &number}) {
        try {
          for (const auto& v : values) spec->check(v, "fuzz");
        } catch (const oitbench::UsageError&) {
        }
      }
    }
    if (total > 2 * oitbench::kMaxRangeValues) __builtin_trap();
  } catch (const oitbench::UsageError&) {
  }
  return 0;
}
