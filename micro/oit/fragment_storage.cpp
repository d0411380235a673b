#include "oit/fragment_storage.hpp"

#include <stdexcept>

#include "oit/fragment_lists.hpp"
#include "oit/packed_arrays.hpp"

namespace oitbench::oit {

const std::vector<std::string>& capture_storage_names() {
  static const std::vector<std::string> names = {"PPLL", "PPPA"};
  return names;
}

CaptureStorage parse_capture_storage(const std::string& name) {
  if (name == "PPLL") return CaptureStorage::PPLL;
  if (name == "PPPA") return CaptureStorage::PPPA;
  throw std::invalid_argument("unknown capture storage '" + name + "' (PPLL, PPPA)");
}

std::unique_ptr<FragmentStorage> make_fragment_storage(CaptureStorage kind, const CaseContext& ctx, size_t initial_pool,
                                                       bool with_counts) {
  if (kind == CaptureStorage::PPPA) return std::make_unique<PackedArrays>(ctx, initial_pool);
  return std::make_unique<FragmentLists>(ctx.width(), ctx.height(), initial_pool, with_counts);
}

std::vector<gl::Program> build_capture_programs(const FragmentStorage& storage, const CaseContext& ctx,
                                                const std::vector<ShaderStage>& stages) {
  std::vector<gl::Program> programs;
  for (const Defines& pass : storage.capture_passes()) {
    Defines d = storage.defines();
    d.insert(d.end(), pass.begin(), pass.end());
    programs.push_back(ctx.build(stages, d));
  }
  return programs;
}

std::vector<GLuint> ids(const std::vector<gl::Program>& programs) {
  std::vector<GLuint> out;
  for (const auto& p : programs) out.push_back(p.get());
  return out;
}

}  // namespace oitbench::oit
