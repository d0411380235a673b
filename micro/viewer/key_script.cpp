#include "viewer/key_script.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>

#include "core/params.hpp"

namespace oitbench::viewer {

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

[[noreturn]] void bad_entry(const std::string& entry, const std::string& why) {
  throw UsageError("--keys: '" + entry + "' " + why +
                   "; expected FRAME:KEY,... where KEY is a letter or digit, shift+LETTER or Esc (e.g. 2:T,4:Z,6:V)");
}

KeyPress parse_key(const std::string& entry, std::string key) {
  KeyPress press;
  for (const char* prefix : {"shift+", "s-"})
    if (lower(key).starts_with(prefix)) {
      press.shift = true;
      key = key.substr(std::char_traits<char>::length(prefix));
      break;
    }
  if (lower(key) == "esc" || lower(key) == "escape") {
    press.key = kEscape;
    return press;
  }
  if (key.size() != 1 || !std::isalnum(static_cast<unsigned char>(key[0]))) bad_entry(entry, "names no key");
  press.key = static_cast<char>(std::toupper(static_cast<unsigned char>(key[0])));
  return press;
}

}  // namespace

std::vector<ScriptedKey> parse_key_script(const std::string& text) {
  std::vector<ScriptedKey> keys;
  size_t start = 0;
  while (start <= text.size()) {
    size_t end = std::min(text.find(',', start), text.size());
    std::string entry = text.substr(start, end - start);
    start = end + 1;
    entry.erase(0, entry.find_first_not_of(" \t"));
    entry.erase(entry.find_last_not_of(" \t") + 1);
    if (entry.empty()) {
      if (end == text.size()) break;
      bad_entry(entry, "is empty");
    }
    size_t colon = entry.find(':');
    if (colon == std::string::npos) bad_entry(entry, "has no ':'");
    ScriptedKey k;
    auto [ptr, ec] = std::from_chars(entry.data(), entry.data() + colon, k.frame);
    if (ec != std::errc() || ptr != entry.data() + colon || k.frame < 0)
      bad_entry(entry, "does not start with a frame number >= 0");
    k.press = parse_key(entry, entry.substr(colon + 1));
    keys.push_back(k);
  }
  // Presses at the same frame keep their order in the script.
  std::stable_sort(keys.begin(), keys.end(),
                   [](const ScriptedKey& a, const ScriptedKey& b) { return a.frame < b.frame; });
  return keys;
}

std::string key_name(KeyPress press) {
  std::string name = press.key == kEscape ? "Esc" : std::string(1, press.key);
  return press.shift ? "shift+" + name : name;
}

}  // namespace oitbench::viewer
