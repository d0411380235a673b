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

TexelBuffer make_texel_buffer(size_t texels, GLenum format, size_t texel_bytes, const std::string& what) {
  GLint max_texels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
  if (texels > static_cast<size_t>(max_texels))
    throw Unsupported(what + " of " + std::to_string(texels) + " fragments exceeds GL_MAX_TEXTURE_BUFFER_SIZE (" +
                      std::to_string(max_texels) + " texels)");
  TexelBuffer b{gl::make_buffer(), gl::make_texture(GL_TEXTURE_BUFFER)};
  glNamedBufferStorage(b.buffer.get(), static_cast<GLsizeiptr>(texels * texel_bytes), nullptr, 0);
  glTextureBuffer(b.view.get(), format, b.buffer.get());
  return b;
}

std::unique_ptr<FragmentStorage> make_fragment_storage(CaptureStorage kind, const CaseContext& ctx, size_t initial_pool,
                                                       bool with_counts) {
  if (kind == CaptureStorage::PPPA) return std::make_unique<PackedArrays>(ctx, initial_pool);
  return std::make_unique<FragmentLists>(ctx.width(), ctx.height(), initial_pool, with_counts);
}

std::vector<gl::Program> build_capture_programs(const FragmentStorage& storage, const CaseContext& ctx,
                                                const std::vector<ShaderStage>& stages, const Defines& extra) {
  std::vector<gl::Program> programs;
  for (const Defines& pass : storage.capture_passes()) {
    Defines d = storage.defines();
    d.insert(d.end(), pass.begin(), pass.end());
    d.insert(d.end(), extra.begin(), extra.end());
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
