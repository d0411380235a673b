#include "viewer/scene_views.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "core/text_position.hpp"

namespace oitbench::viewer {

namespace {

// A JSON reader that only finds where things are: the files it reads have passed parse_scene, so
// it checks no more than it needs to stay inside the text.
class JsonScanner {
 public:
  JsonScanner(const std::string& path, const std::string& text) : path_(path), t_(text) {}

  size_t skip_ws(size_t i) const {
    while (i < t_.size() && std::isspace(static_cast<unsigned char>(t_[i]))) ++i;
    return i;
  }
  // i at an opening quote; returns the index after the closing one.
  size_t skip_string(size_t i) const {
    for (++i; i < t_.size(); ++i) {
      if (t_[i] == '\\')
        ++i;
      else if (t_[i] == '"')
        return i + 1;
    }
    fail(i, "unterminated string");
  }
  // Returns the index after the value starting at (or after whitespace from) i.
  size_t skip_value(size_t i) const {
    i = skip_ws(i);
    if (i >= t_.size()) fail(i, "expected a value");
    if (t_[i] == '"') return skip_string(i);
    if (t_[i] == '{' || t_[i] == '[') {
      int depth = 0;
      for (; i < t_.size(); ++i) {
        char c = t_[i];
        if (c == '"') {
          i = skip_string(i) - 1;
        } else if (c == '{' || c == '[') {
          ++depth;
        } else if ((c == '}' || c == ']') && --depth == 0) {
          return i + 1;
        }
      }
      fail(i, "unbalanced brackets");
    }
    while (i < t_.size() && !std::strchr(",}] \t\r\n", t_[i])) ++i;
    return i;
  }

  struct Member {
    std::string key;  // as written between the quotes
    size_t key_at, value_at, value_end;
  };
  // The members of the object whose '{' is at `open`, and the index of its '}'.
  std::vector<Member> members(size_t open, size_t& close) const {
    if (open >= t_.size() || t_[open] != '{') fail(open, "expected an object");
    std::vector<Member> out;
    size_t i = skip_ws(open + 1);
    if (i < t_.size() && t_[i] == '}') {
      close = i;
      return out;
    }
    while (true) {
      i = skip_ws(i);
      if (i >= t_.size() || t_[i] != '"') fail(i, "expected a key");
      Member m;
      m.key_at = i;
      size_t key_end = skip_string(i);
      m.key = t_.substr(i + 1, key_end - i - 2);
      i = skip_ws(key_end);
      if (i >= t_.size() || t_[i] != ':') fail(i, "expected ':'");
      m.value_at = skip_ws(i + 1);
      m.value_end = skip_value(m.value_at);
      out.push_back(m);
      i = skip_ws(m.value_end);
      if (i < t_.size() && t_[i] == ',') {
        ++i;
        continue;
      }
      if (i < t_.size() && t_[i] == '}') {
        close = i;
        return out;
      }
      fail(i, "expected ',' or '}'");
    }
  }

  // The "views" object of the root: its '{' and '}'.
  std::pair<size_t, size_t> views_object() const {
    size_t close = 0;
    for (const auto& m : members(skip_ws(0), close))
      if (m.key == "views") {
        if (t_[m.value_at] != '{') fail(m.value_at, "\"views\" is not an object");
        size_t views_close = 0;
        members(m.value_at, views_close);
        return {m.value_at, views_close};
      }
    fail(0, "the scene has no \"views\" object");
  }

  [[noreturn]] void fail(size_t at, const std::string& what) const {
    throw oit::SceneError(path_ + ":" + line_column(t_, std::min(at, t_.size())) + ": " + what);
  }

 private:
  const std::string& path_;
  const std::string& t_;
};

// Whitespace from the start of the line holding `at` up to `at`, if only whitespace precedes it.
std::optional<std::string> line_indent(const std::string& text, size_t at) {
  size_t start = text.rfind('\n', at == 0 ? 0 : at - 1);
  start = start == std::string::npos ? 0 : start + 1;
  std::string prefix = text.substr(start, at - start);
  if (prefix.find_first_not_of(" \t") != std::string::npos) return std::nullopt;
  return prefix;
}

// Four decimals are far below what anyone steers a camera to; the shortest form reads back exactly.
std::string number(float v) {
  double r = std::round(static_cast<double>(v) * 1e4) / 1e4;
  if (r == 0) r = 0;  // no "-0"
  char buf[32];
  auto [end, ec] = std::to_chars(buf, buf + sizeof buf, r);
  return std::string(buf, end);
}

std::string vec3(glm::vec3 v) { return "[" + number(v.x) + ", " + number(v.y) + ", " + number(v.z) + "]"; }

const char* order_text(oit::SubmitOrder o) {
  switch (o) {
    case oit::SubmitOrder::FrontToBack:
      return "front-to-back";
    case oit::SubmitOrder::BackToFront:
      return "back-to-front";
    default:
      return "as-generated";
  }
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read scene file " + path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

std::vector<std::string> view_names_in_file_order(const std::string& path, const std::string& text) {
  JsonScanner scan(path, text);
  auto [open, close] = scan.views_object();
  std::vector<std::string> names;
  for (const auto& m : scan.members(open, close))
    names.push_back(nlohmann::json::parse("\"" + m.key + "\"").get<std::string>());
  return names;
}

std::string unique_view_name(const std::vector<std::string>& taken, const std::string& wanted) {
  auto free = [&](const std::string& n) { return std::find(taken.begin(), taken.end(), n) == taken.end(); };
  if (!wanted.empty() && free(wanted)) return wanted;
  std::string base = wanted.empty() ? "view" : wanted;
  for (int i = wanted.empty() ? 1 : 2;; ++i)
    if (free(base + "-" + std::to_string(i))) return base + "-" + std::to_string(i);
}

std::string view_json(const oit::View& v) {
  return "{ \"eye\": " + vec3(v.eye) + ", \"target\": " + vec3(v.target) + ", \"up\": " + vec3(v.up) +
         ", \"fov\": " + number(v.fov_deg) + ", \"order\": \"" + order_text(v.order) + "\" }";
}

std::string insert_view(const std::string& path, const std::string& text, const oit::View& view) {
  JsonScanner scan(path, text);
  auto [open, close] = scan.views_object();
  std::string entry = nlohmann::json(view.name).dump() + ": " + view_json(view);
  size_t views_close = close;
  auto members = scan.members(open, views_close);
  std::string out = text;
  if (members.empty()) {
    // "views": {} -> one entry on its own line when the braces are on separate lines
    auto indent = line_indent(text, close);
    if (indent && text.find('\n', open) < close) {
      out.insert(close, "  " + entry + "\n" + *indent);
    } else {
      out.insert(close, " " + entry + " ");
    }
    return out;
  }
  // After the last entry: on a line of its own indented like the first entry, or on the same line
  // when the first entry shares its line with the brace.
  auto indent = line_indent(text, members.front().key_at);
  out.insert(members.back().value_end, indent ? ",\n" + *indent + entry : ", " + entry);
  return out;
}

std::string save_view_to_scene_file(const std::string& path, oit::View view, const std::string& wanted) {
  std::string text = slurp(path);
  oit::parse_scene(path, text);  // the file as it is now must be a scene: never build on a broken one
  view.name = unique_view_name(view_names_in_file_order(path, text), wanted);
  std::string updated = insert_view(path, text, view);
  oit::SceneDesc check = oit::parse_scene(path, updated);
  const oit::View& saved = check.view(view.name);
  if (glm::length(saved.eye - view.eye) > 1e-3f)
    throw oit::SceneError(path + ": the saved view \"" + view.name + "\" reads back with another eye");
  std::string tmp = path + ".oitbench-tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot write " + tmp);
    out << updated;
    if (!out.flush()) throw std::runtime_error("cannot write " + tmp);
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp);
    throw std::runtime_error("cannot replace " + path + ": " + ec.message());
  }
  return view.name;
}

}  // namespace oitbench::viewer
