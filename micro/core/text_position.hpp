#pragma once
// "LINE:COLUMN" (both from 1) of a byte offset in a text: how data-file errors name their place.
#include <cstddef>
#include <string>
#include <vector>

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

// nlohmann keeps no positions of values: the byte offset in a JSON text (already parsed, so well formed) of
// the entry at `path` (object keys as written, array indices as decimal numbers): an object member's key,
// an array element's first character. Where the path leaves the text, the deepest part found.
size_t json_path_offset(const std::string& text, const std::vector<std::string>& path);

// Where a JSON text broke a parse that reports no position (nlohmann's "number overflow parsing
// '1e400'"): the first place the quoted token of `message` occurs; 0 when it names none.
size_t json_error_offset(const std::string& text, const std::string& message);

}  // namespace oitbench
