// libFuzzer harness: the 3DGS PLY reader (micro/oit/splats/splat_ply.cpp). Any bytes must give splats or
// a SplatFileError, never another exception, a crash, a hang or memory beyond what the file can hold
// (the reader refuses counts its size cannot back before it allocates). The input is written to a file
// in the current folder (run.sh runs each harness in its build folder), as the reader reads files.
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>

#include "oit/splats/splat_ply.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace oitbench::oit;
  const std::string path = "splat_ply_fuzz_input.ply";
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    SplatPlyHeader h = read_splat_ply_header(path);
    SplatList s = read_splat_ply(path, glm::vec3(0.0f, 0.0f, 3.0f));
    if (s.size() != h.count) __builtin_trap();
    check_splat_ply(path);
  } catch (const SplatFileError&) {
  }
  return 0;
}
