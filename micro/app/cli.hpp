#pragma once
#include <string>
#include <vector>

namespace oitbench {
// The whole command line: `oitbench list|info|run ...`. Returns the exit code
// (0 done, 1 failure, 2 usage error, 3 nothing could run on this driver, 130 interrupted).
int run_cli(int argc, char** argv);
}  // namespace oitbench
