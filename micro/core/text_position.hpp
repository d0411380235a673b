#pragma once
// "LINE:COLUMN" (both from 1) of a byte offset in a text: how data-file errors name their place.
#include <cstddef>
#include <string>

namespace oitbench {

inline std::string line_column(const std::string& text, size_t byte) {
  size_t line = 1, col = 1;
  for (size_t i = 0; i < byte && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
  }
  return std::to_string(line) + ":" + std::to_string(col);
}

}  // namespace oitbench
