// libFuzzer harness: the CSV reader and the append check run on an existing --out file. Any bytes must
// give rows, or a CsvError; an append decision must never be taken on a file whose header differs.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/csv.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::vector<std::string> columns = {"experiment", "variant", "pass", "status", "median_ms"};
  try {
    auto rows = oitbench::csv_parse(text);
    for (const auto& r : rows)
      if (r.empty()) __builtin_trap();  // a row has at least one field
  } catch (const oitbench::CsvError&) {
  }
  try {
    const std::string head = text.substr(0, oitbench::kCsvHeadBytes);
    const char last = text.empty() ? '\n' : text.back();
    auto action = oitbench::csv_append_action(head, text.size(), last, columns, "fuzz.csv");
    if (action != oitbench::AppendAction::WriteHeader) {
      auto first = oitbench::csv_parse(text.substr(0, text.find('\n')) + "\n");
      std::vector<std::string> header = first.empty() ? std::vector<std::string>{} : first[0];
      if (header != columns) __builtin_trap();  // appending only under the same header
    } else if (!text.empty()) {
      __builtin_trap();  // the header is written only into an empty file
    }
  } catch (const oitbench::CsvError&) {
  }
  return 0;
}
