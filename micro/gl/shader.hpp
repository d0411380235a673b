#pragma once
// GLSL assembly: `#version` preamble, the case's injected defines, `#include "file"` resolved
// relative to the including file, and `#line L S` markers so a driver's log can be mapped back
// from (source-string, line) to the real file and line.
#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "gl/gl_objects.hpp"

namespace oitbench {

using Defines = std::vector<std::pair<std::string, std::string>>;

struct AssembledSource {
  std::string text;
  std::vector<std::string> files;  // index = GLSL source-string number used in #line
};

struct ShaderStage {
  GLenum stage;
  std::string path;  // relative to the shader root, e.g. "occupancy/occupancy.frag"
};

class ShaderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class ShaderLibrary {
 public:
  explicit ShaderLibrary(std::filesystem::path root, std::string version = "450 core");

  const std::filesystem::path& root() const { return root_; }

  // Throws ShaderError for a missing file or an include cycle.
  AssembledSource assemble(const std::string& path, const Defines& defines) const;
  // Assembles from text already in memory (tests, generated code); includes resolve from the root.
  AssembledSource assemble_text(const std::string& name, const std::string& text, const Defines& defines) const;

  // "sorts/insertion.glsl@1a2b3c4d": the path (relative to the root) and the FNV-1a 32-bit hash of
  // the file's bytes as read now, in hex; names the code a case ran (the `sort_source` column).
  // Throws ShaderError for a missing file.
  std::string source_id(const std::string& relative_path) const;

  // Compiles and links; throws ShaderError whose message holds the mapped log and the defines.
  // With a program cache, a program linked before (same sources, defines and driver) is loaded
  // from its glGetProgramBinary image instead: big unrolled sorts compile for seconds.
  gl::Program build(const std::vector<ShaderStage>& stages, const Defines& defines) const;

  // Enables the program-binary cache in `dir` (created on demand); an empty path disables it.
  // `driver` (vendor, renderer, version) is part of every key.
  void enable_program_cache(std::filesystem::path dir, std::string driver);
  struct CacheCounts {
    unsigned hits = 0, misses = 0;
  };
  CacheCounts cache_counts() const { return counts_; }

 private:
  gl::Program compile_and_link(const std::vector<ShaderStage>& stages, const std::vector<AssembledSource>& sources,
                               const Defines& defines) const;

  std::filesystem::path root_;
  std::string version_;
  std::filesystem::path cache_dir_;
  std::string driver_;
  mutable CacheCounts counts_;
};

// Where the program cache lives by default: $XDG_CACHE_HOME/oitbench/programs or ~/.cache/oitbench/programs.
std::filesystem::path default_program_cache_dir();

// Rewrites driver log locations ("0:12(3):" Mesa, "0(12) :" NVIDIA/AMD) into "file:line:".
std::string map_shader_log(const std::string& log, const AssembledSource& source);
std::string format_defines(const Defines& defines);

}  // namespace oitbench
