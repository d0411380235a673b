#pragma once
// Keys as the viewer understands them, from the keyboard or from `oitbench view --keys SCRIPT`
// ("2:T,4:Z,6:shift+M,8:V": press T before frame 2, ...), so a test can switch techniques, toggle
// the depth view and save a view without a person at the keyboard.
#include <string>
#include <vector>

namespace oitbench::viewer {

inline constexpr char kEscape = 27;

struct KeyPress {
  char key = 0;  // 'A'..'Z', '0'..'9' or kEscape
  bool shift = false;
  bool operator==(const KeyPress&) const = default;
};

struct ScriptedKey {
  int frame = 0;  // pressed before this frame renders (0 = the first)
  KeyPress press;
};

// Parses "FRAME:KEY,FRAME:KEY,..."; KEY is a letter or digit, optionally "shift+" before it, or
// "Esc". Throws UsageError naming the bad entry and the syntax.
std::vector<ScriptedKey> parse_key_script(const std::string& text);

std::string key_name(KeyPress press);  // "T", "shift+M", "Esc"

}  // namespace oitbench::viewer
