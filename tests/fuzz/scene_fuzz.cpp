// libFuzzer harness: the scene parser, then the mesh of the first view under a small cap (the size
// estimate must refuse what would pass it before building). Any text must give a mesh or a
// SceneError, never another exception, a crash, a hang or unbounded memory. Scenes with a model or a
// ply object are parsed but not built (their files are on disk; the unit tests and the splat_ply
// harness cover them).
#include <cstddef>
#include <cstdint>
#include <string>

#include "oit/scene/scene.hpp"

namespace {
constexpr unsigned long long kFuzzMeshBytes = 16ull << 20;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  using namespace oitbench::oit;
  try {
    SceneDesc s = parse_scene("fuzz.json", text);
    bool model = false;
    for (const auto& o : s.objects) model = model || o.generator == "model" || o.generator == "ply";
    if (model || s.views.empty()) return 0;
    for (Detail d : {Detail::Small, Detail::Full}) {
      Mesh m = build_mesh(s, s.views.front(), d, true, kFuzzMeshBytes);
      // The estimate bounds what was built (vertices are the bulk of it).
      if (m.vertices.size() * sizeof(Vertex) + m.splats.size() * sizeof(Splat) > kFuzzMeshBytes) __builtin_trap();
    }
  } catch (const SceneError&) {
  }
  return 0;
}
