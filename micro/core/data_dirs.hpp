#pragma once
// Where oitbench's data lives (shaders/, scenes/, presets/): the one lookup every layer uses.
#include <string>

namespace oitbench {

// The folder for `kind` ("shaders", "scenes" or "presets"), in this order:
//   1. $OITBENCH_SHADERS, $OITBENCH_SCENES or $OITBENCH_PRESETS;
//   2. walking up from the running binary: DIR/KIND or DIR/share/oitbench/KIND, where it holds the
//      kind's marker file (a build tree beside the sources, an install prefix, an unpacked bundle);
//   3. the source tree the binary was built from.
// Throws std::invalid_argument for another kind.
std::string data_dir(const std::string& kind);

// The same lookup, saying which rule found it: `from` is "$OITBENCH_SHADERS" (the variable's name),
// "walking up from the binary" or "the source tree" (the fallback, whether or not it exists).
struct DataDirLookup {
  std::string path, from;
};
DataDirLookup find_data_dir(const std::string& kind);

}  // namespace oitbench
