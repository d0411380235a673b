#include "oit/fragment_storage.hpp"

#include <bit>
#include <stdexcept>

#include "oit/fragment_lists.hpp"
#include "oit/packed_arrays.hpp"
#include "oit/packed_fragment.hpp"

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

const std::vector<std::string>& frag_colour_names() {
  static const std::vector<std::string> names = {"rgba8", "rgba16f", "rgba32f"};
  return names;
}

const std::vector<std::string>& frag_depth_names() {
  static const std::vector<std::string> names = {"window", "view"};
  return names;
}

FragFormat parse_frag_format(const std::string& colour, const std::string& depth) {
  FragFormat f;
  if (colour == "rgba8")
    f.colour = FragColour::RGBA8;
  else if (colour == "rgba16f")
    f.colour = FragColour::RGBA16F;
  else if (colour == "rgba32f")
    f.colour = FragColour::RGBA32F;
  else
    throw std::invalid_argument("unknown fragment colour format '" + colour + "' (rgba8, rgba16f, rgba32f)");
  if (depth == "window")
    f.depth = FragDepth::Window;
  else if (depth == "view")
    f.depth = FragDepth::View;
  else
    throw std::invalid_argument("unknown fragment depth format '" + depth + "' (window, view)");
  return f;
}

Defines frag_format_defines(FragFormat f) {
  const char* c = f.colour == FragColour::RGBA8     ? "FRAG_COLOUR_RGBA8"
                  : f.colour == FragColour::RGBA16F ? "FRAG_COLOUR_RGBA16F"
                                                    : "FRAG_COLOUR_RGBA32F";
  return {{c, ""}, {f.depth == FragDepth::View ? "FRAG_DEPTH_VIEW" : "FRAG_DEPTH_WINDOW", ""}};
}

size_t frag_node_bytes(FragColour c) { return c == FragColour::RGBA8 ? 8 : c == FragColour::RGBA16F ? 12 : 20; }

glm::dvec4 node_colour(const HostLists& h, size_t n) {
  if (h.colour == FragColour::RGBA8) {
    unsigned c = h.nodes[n].x;
    return {(c & 0xffu) / 255.0, ((c >> 8) & 0xffu) / 255.0, ((c >> 16) & 0xffu) / 255.0, (c >> 24) / 255.0};
  }
  const glm::uvec4& w = h.wide[n];
  if (h.colour == FragColour::RGBA16F)
    return {half_to_float(static_cast<uint16_t>(w.x & 0xffffu)), half_to_float(static_cast<uint16_t>(w.x >> 16)),
            half_to_float(static_cast<uint16_t>(w.y & 0xffffu)), half_to_float(static_cast<uint16_t>(w.y >> 16))};
  return {std::bit_cast<float>(w.x), std::bit_cast<float>(w.y), std::bit_cast<float>(w.z), std::bit_cast<float>(w.w)};
}

std::array<unsigned, 4> node_tie_key(const HostLists& h, size_t n) {
  if (h.colour == FragColour::RGBA8) return {h.nodes[n].x, 0, 0, 0};
  const glm::uvec4& w = h.wide[n];
  if (h.colour == FragColour::RGBA16F) return {w.y, w.x, 0, 0};  // (a, b) then (g, r): the high half first
  return {w.w, w.z, w.y, w.x};
}

NodePool::NodePool(size_t pool, FragColour colour, const std::string& what) : colour_(colour) {
  if (colour == FragColour::RGBA8) {
    colours_ = make_texel_buffer(pool, GL_RG32UI, 8, what);
    return;
  }
  colours_ = colour == FragColour::RGBA16F ? make_texel_buffer(pool, GL_RG32UI, 8, what)
                                           : make_texel_buffer(pool, GL_RGBA32UI, 16, what);
  depths_ = make_texel_buffer(pool, GL_R32UI, 4, what);
}

void NodePool::bind() const {
  GLenum f = colour_ == FragColour::RGBA32F ? GL_RGBA32UI : GL_RG32UI;
  glBindImageTexture(kNodesUnit, colours_.view.get(), 0, GL_FALSE, 0, GL_READ_WRITE, f);
  if (colour_ != FragColour::RGBA8)
    glBindImageTexture(kNodeDepthUnit, depths_.view.get(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
}

void NodePool::read(size_t n, HostLists& h) const {
  h.colour = colour_;
  h.nodes.assign(n, glm::uvec2(0));
  if (!n) return;
  if (colour_ == FragColour::RGBA8) {
    glGetNamedBufferSubData(colours_.buffer.get(), 0, static_cast<GLsizeiptr>(n * 8), h.nodes.data());
    return;
  }
  std::vector<unsigned> depth(n);
  glGetNamedBufferSubData(depths_.buffer.get(), 0, static_cast<GLsizeiptr>(n * 4), depth.data());
  h.wide.assign(n, glm::uvec4(0));
  if (colour_ == FragColour::RGBA32F) {
    glGetNamedBufferSubData(colours_.buffer.get(), 0, static_cast<GLsizeiptr>(n * 16), h.wide.data());
  } else {
    std::vector<glm::uvec2> c(n);
    glGetNamedBufferSubData(colours_.buffer.get(), 0, static_cast<GLsizeiptr>(n * 8), c.data());
    for (size_t i = 0; i < n; ++i) h.wide[i] = glm::uvec4(c[i], 0u, 0u);
  }
  for (size_t i = 0; i < n; ++i) h.nodes[i].y = depth[i];
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
                                                       bool with_counts, FragFormat format) {
  if (kind == CaptureStorage::PPPA) return std::make_unique<PackedArrays>(ctx, initial_pool, format);
  return std::make_unique<FragmentLists>(ctx.width(), ctx.height(), initial_pool, with_counts, format);
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
