#include "core/text_position.hpp"

#include <algorithm>
#include <cctype>

namespace oitbench {

namespace {

// A cursor over well-formed JSON that skips values without building them.
struct JsonCursor {
  const std::string& t;
  size_t i = 0;

  bool at(char c) const { return i < t.size() && t[i] == c; }
  void space() {
    while (i < t.size() && std::isspace(static_cast<unsigned char>(t[i]))) ++i;
  }
  // At a '"': the string as written (escapes kept), the cursor after its closing quote.
  std::string string() {
    std::string s;
    for (++i; i < t.size() && t[i] != '"'; ++i) {
      if (t[i] == '\\' && i + 1 < t.size()) s += t[i++];
      s += t[i];
    }
    ++i;
    return s;
  }
  // After a member's or an element's value: past it and its comma; false at the container's end.
  bool next() {
    value();
    space();
    if (!at(',')) return false;
    ++i;
    return true;
  }
  void value() {
    space();
    if (at('"')) {
      string();
    } else if (at('{') || at('[')) {
      const bool object = at('{');
      const char close = object ? '}' : ']';
      ++i;
      space();
      while (i < t.size() && !at(close)) {
        if (object) {
          string();
          space();
          ++i;  // ':'
        }
        value();
        space();
        if (at(',')) ++i;
        space();
      }
      ++i;
    } else {
      while (i < t.size() && !at(',') && !at('}') && !at(']') && !std::isspace(static_cast<unsigned char>(t[i]))) ++i;
    }
  }
};

}  // namespace

size_t json_path_offset(const std::string& text, const std::vector<std::string>& path) {
  JsonCursor c{text};
  size_t best = 0;
  c.space();
  for (const auto& key : path) {
    c.space();
    bool found = false;
    if (c.at('{')) {
      ++c.i;
      for (c.space(); c.at('"') && !found; c.space()) {
        const size_t key_at = c.i;
        found = c.string() == key;
        c.space();
        ++c.i;  // ':'
        if (found)
          best = key_at;
        else if (!c.next())
          break;
      }
    } else if (c.at('[') && !key.empty() && std::all_of(key.begin(), key.end(), ::isdigit)) {
      const size_t index = std::stoul(key);
      ++c.i;
      for (size_t n = 0; !found; ++n) {
        c.space();
        if (c.i >= text.size() || c.at(']')) break;
        found = n == index;
        if (found)
          best = c.i;
        else if (!c.next())
          break;
      }
    }
    if (!found) break;
  }
  return best;
}

size_t json_error_offset(const std::string& text, const std::string& message) {
  auto open = message.find('\'');
  auto close = open == std::string::npos ? std::string::npos : message.find('\'', open + 1);
  if (close == std::string::npos || close == open + 1) return 0;
  auto at = text.find(message.substr(open + 1, close - open - 1));
  return at == std::string::npos ? 0 : at;
}

}  // namespace oitbench
