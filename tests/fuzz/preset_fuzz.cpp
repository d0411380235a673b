// libFuzzer harness: the preset parser. Any text must give a preset or a UsageError naming the file,
// never another exception, a crash or unbounded work.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/presets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    auto p = oitbench::parse_preset("fuzz", "fuzz.json", text);
    for (const auto& r : p.runs)
      for (const auto& [name, values] : r.overrides)
        if (values.empty()) __builtin_trap();  // an empty list is refused by the parser
  } catch (const oitbench::UsageError& e) {
    if (std::string(e.what()).rfind("fuzz.json", 0) != 0) __builtin_trap();  // every message names the file
  }
  return 0;
}
