#include "gl/shader.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <regex>
#include <set>
#include <sstream>

namespace oitbench {
namespace {

std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  if (!in) throw ShaderError("cannot open shader file " + p.string());
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct Assembler {
  const std::filesystem::path& root;
  AssembledSource out;
  std::vector<std::string> stack;
  std::set<std::string> included;

  int file_index(const std::string& name) {
    out.files.push_back(name);
    return static_cast<int>(out.files.size()) - 1;
  }

  std::filesystem::path resolve(const std::string& include, const std::filesystem::path& from_dir) {
    for (const auto& base : {from_dir, root}) {
      auto candidate = (base / include).lexically_normal();
      if (std::filesystem::exists(candidate)) return candidate;
    }
    throw ShaderError("shader include \"" + include + "\" not found (searched " + from_dir.string() + " and " +
                      root.string() + ")");
  }

  std::string display_name(const std::filesystem::path& p) const {
    auto rel = p.lexically_relative(root);
    return (rel.empty() || rel.native().starts_with("..")) ? p.string() : ("shaders/" + rel.string());
  }

  void emit(const std::string& name, const std::string& text, const std::filesystem::path& dir) {
    if (std::find(stack.begin(), stack.end(), name) != stack.end())
      throw ShaderError("shader include cycle at " + name);
    stack.push_back(name);
    const int idx = file_index(name);
    out.text += "#line 1 " + std::to_string(idx) + "\n";
    static const std::regex include_re(R"(^\s*#\s*include\s+\"([^\"]+)\"\s*$)");
    std::istringstream lines(text);
    std::string line;
    int lineno = 0;
    while (std::getline(lines, line)) {
      ++lineno;
      std::smatch m;
      if (std::regex_match(line, m, include_re)) {
        auto path = resolve(m[1].str(), dir);
        auto child = display_name(path);
        if (included.insert(child).second) emit(child, read_file(path), path.parent_path());
        out.text += "#line " + std::to_string(lineno + 1) + " " + std::to_string(idx) + "\n";
      } else {
        out.text += line;
        out.text += '\n';
      }
    }
    stack.pop_back();
  }
};

std::string preamble(const std::string& version, const Defines& defines) {
  std::string p = "#version " + version + "\n";
  for (const auto& [k, v] : defines) p += "#define " + k + (v.empty() ? "" : " " + v) + "\n";
  return p;
}

// Whether a shader's compile or a program's link (`status`) failed; if so, `log` gets its info log.
// Get and GetLog are the object's glGet*iv and glGet*InfoLog.
template <class Get, class GetLog>
bool failed(GLuint object, GLenum status, Get get, GetLog get_log, std::string& log) {
  GLint ok = 0;
  get(object, status, &ok);
  if (ok) return false;
  GLint len = 0;
  get(object, GL_INFO_LOG_LENGTH, &len);
  log.assign(static_cast<size_t>(std::max(len, 1)), '\0');
  get_log(object, len, nullptr, log.data());
  log.resize(std::strlen(log.c_str()));
  return true;
}

}  // namespace

ShaderLibrary::ShaderLibrary(std::filesystem::path root, std::string version)
    : root_(std::move(root)), version_(std::move(version)) {}

AssembledSource ShaderLibrary::assemble_text(const std::string& name, const std::string& text,
                                             const Defines& defines) const {
  Assembler a{root_, {}, {}, {}};
  a.file_index("<preamble: #version and injected defines>");
  a.out.text = preamble(version_, defines);
  a.emit(name, text, root_);
  return a.out;
}

std::string ShaderLibrary::source_id(const std::string& relative_path) const {
  uint32_t h = 2166136261u;  // FNV-1a, 32 bits
  for (unsigned char c : read_file(root_ / relative_path)) h = (h ^ c) * 16777619u;
  char hex[9];
  std::snprintf(hex, sizeof hex, "%08x", static_cast<unsigned>(h));
  return relative_path + "@" + hex;
}

AssembledSource ShaderLibrary::assemble(const std::string& path, const Defines& defines) const {
  auto full = root_ / path;
  Assembler a{root_, {}, {}, {}};
  a.file_index("<preamble: #version and injected defines>");
  a.out.text = preamble(version_, defines);
  auto name = a.display_name(full);
  a.included.insert(name);
  a.emit(name, read_file(full), full.parent_path());
  return a.out;
}

std::string map_shader_log(const std::string& log, const AssembledSource& source) {
  // Mesa: "0:12(3): error: ..."  NVIDIA: "0(12) : error C1008: ..."
  static const std::regex mesa_re(R"((^|\n)(\d+):(\d+)\((\d+)\))");
  static const std::regex nv_re(R"((^|\n)(\d+)\((\d+)\) ?)");
  auto name_of = [&](const std::string& idx) {
    size_t i = std::stoul(idx);
    return i < source.files.size() ? source.files[i] : "<source " + idx + ">";
  };
  std::string out;
  std::smatch m;
  std::string rest = log;
  if (std::regex_search(log, mesa_re)) {
    while (std::regex_search(rest, m, mesa_re)) {
      out += m.prefix().str() + m[1].str() + name_of(m[2].str()) + ":" + m[3].str() + ":" + m[4].str();
      rest = m.suffix().str();
    }
  } else {
    while (std::regex_search(rest, m, nv_re)) {
      out += m.prefix().str() + m[1].str() + name_of(m[2].str()) + ":" + m[3].str();
      rest = m.suffix().str();
    }
  }
  return out + rest;
}

std::string format_defines(const Defines& defines) {
  std::string s;
  for (const auto& [k, v] : defines) s += (s.empty() ? "" : " ") + k + (v.empty() ? "" : "=" + v);
  return s.empty() ? "(none)" : s;
}

gl::Program ShaderLibrary::compile_and_link(const std::vector<ShaderStage>& stages,
                                            const std::vector<AssembledSource>& sources, const Defines& defines) const {
  gl::Program program(glCreateProgram());
  std::vector<gl::Shader> shaders;
  for (size_t i = 0; i < stages.size(); ++i) {
    const auto& st = stages[i];
    const auto& src = sources[i];
    gl::Shader sh(glCreateShader(st.stage));
    const char* text = src.text.c_str();
    glShaderSource(sh.get(), 1, &text, nullptr);
    glCompileShader(sh.get());
    std::string log;
    if (failed(sh.get(), GL_COMPILE_STATUS, glGetShaderiv, glGetShaderInfoLog, log))
      throw ShaderError("compile error in shaders/" + st.path + " with defines [" + format_defines(defines) + "]:\n" +
                        map_shader_log(log, src));
    glAttachShader(program.get(), sh.get());
    shaders.push_back(std::move(sh));
  }
  if (!cache_dir_.empty()) glProgramParameteri(program.get(), GL_PROGRAM_BINARY_RETRIEVABLE_HINT, GL_TRUE);
  glLinkProgram(program.get());
  std::string log;
  if (failed(program.get(), GL_LINK_STATUS, glGetProgramiv, glGetProgramInfoLog, log)) {
    std::string names;
    for (const auto& st : stages) names += (names.empty() ? "" : " + ") + ("shaders/" + st.path);
    throw ShaderError("link error in " + names + " with defines [" + format_defines(defines) + "]:\n" + log);
  }
  for (const auto& sh : shaders) glDetachShader(program.get(), sh.get());
  return program;
}

namespace {
// FNV-1a: a stable 64-bit key for the cache file name (std::hash is not stable across builds).
uint64_t fnv1a(const std::string& s, uint64_t h = 1469598103934665603ull) {
  for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
  return h;
}
}  // namespace

std::filesystem::path default_program_cache_dir() {
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return std::filesystem::path(x) / "oitbench" / "programs";
  if (const char* h = std::getenv("HOME"); h && *h)
    return std::filesystem::path(h) / ".cache" / "oitbench" / "programs";
  return {};
}

void ShaderLibrary::enable_program_cache(std::filesystem::path dir, std::string driver) {
  cache_dir_ = std::move(dir);
  driver_ = std::move(driver);
}

gl::Program ShaderLibrary::build(const std::vector<ShaderStage>& stages, const Defines& defines) const {
  std::vector<AssembledSource> sources;
  std::string key_text = driver_;
  for (const auto& st : stages) {
    sources.push_back(assemble(st.path, defines));
    key_text += "\n--stage " + std::to_string(st.stage) + "\n" + sources.back().text;
  }
  if (cache_dir_.empty()) return compile_and_link(stages, sources, defines);

  char name[32];
  std::snprintf(name, sizeof name, "%016llx.bin", static_cast<unsigned long long>(fnv1a(key_text)));
  auto path = cache_dir_ / name;
  // The file holds the binary format, the full key (to rule out hash collisions), then the image.
  if (std::ifstream in{path, std::ios::binary}) {
    GLenum format = 0;
    uint64_t key_size = 0;
    in.read(reinterpret_cast<char*>(&format), sizeof format);
    in.read(reinterpret_cast<char*>(&key_size), sizeof key_size);
    std::string key(key_size < (1u << 28) ? key_size : 0, '\0');
    in.read(key.data(), static_cast<std::streamsize>(key.size()));
    const bool header_ok = in.good() && key == key_text;
    std::string image((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (header_ok && !image.empty()) {
      gl::Program program(glCreateProgram());
      glProgramBinary(program.get(), format, image.data(), static_cast<GLsizei>(image.size()));
      GLint ok = 0;
      glGetProgramiv(program.get(), GL_LINK_STATUS, &ok);
      while (glGetError() != GL_NO_ERROR) {
      }
      if (ok) {
        ++counts_.hits;
        return program;
      }
    }
  }
  ++counts_.misses;
  auto program = compile_and_link(stages, sources, defines);
  GLint length = 0;
  glGetProgramiv(program.get(), GL_PROGRAM_BINARY_LENGTH, &length);
  if (length > 0) {
    std::string image(static_cast<size_t>(length), '\0');
    GLenum format = 0;
    glGetProgramBinary(program.get(), length, nullptr, &format, image.data());
    std::error_code ec;
    std::filesystem::create_directories(cache_dir_, ec);
    auto tmp = path;
    tmp += ".tmp" + std::to_string(::getpid());
    if (std::ofstream out{tmp, std::ios::binary}) {
      uint64_t key_size = key_text.size();
      out.write(reinterpret_cast<const char*>(&format), sizeof format);
      out.write(reinterpret_cast<const char*>(&key_size), sizeof key_size);
      out << key_text << image;
      out.close();
      std::filesystem::rename(tmp, path, ec);  // atomic: concurrent runs never read half a file
    }
  }
  return program;
}

}  // namespace oitbench
