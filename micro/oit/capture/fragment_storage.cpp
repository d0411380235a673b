#include "oit/capture/fragment_storage.hpp"

#include <algorithm>
#include <bit>
#include <cstdlib>
#include <stdexcept>

#include "oit/capture/fragment_lists.hpp"
#include "oit/capture/packed_arrays.hpp"
#include "oit/capture/packed_fragment.hpp"

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

NodePool::NodePool(size_t pool, FragColour colour, const std::string& what, size_t min_chunks) : colour_(colour) {
  if (colour == FragColour::RGBA8) {
    colours_ = ChunkedTexels(pool, GL_RG32UI, 8, what, min_chunks);
    return;
  }
  colours_ = colour == FragColour::RGBA16F ? ChunkedTexels(pool, GL_RG32UI, 8, what, min_chunks)
                                           : ChunkedTexels(pool, GL_RGBA32UI, 16, what, min_chunks);
  depths_ = ChunkedTexels(pool, GL_R32UI, 4, what, min_chunks);
}

void NodePool::bind() const {
  colours_.bind(kNodesUnit, ChunkSlot::Colours);
  if (colour_ != FragColour::RGBA8) depths_.bind(kNodeDepthUnit, ChunkSlot::Depths);
}

void NodePool::read(size_t n, HostLists& h) const {
  h.colour = colour_;
  h.nodes.assign(n, glm::uvec2(0));
  if (!n) return;
  if (colour_ == FragColour::RGBA8) {
    colours_.read(n, h.nodes.data());
    return;
  }
  std::vector<unsigned> depth(n);
  depths_.read(n, depth.data());
  h.wide.assign(n, glm::uvec4(0));
  if (colour_ == FragColour::RGBA32F) {
    colours_.read(n, h.wide.data());
  } else {
    std::vector<glm::uvec2> c(n);
    colours_.read(n, c.data());
    for (size_t i = 0; i < n; ++i) h.wide[i] = glm::uvec4(c[i], 0u, 0u);
  }
  for (size_t i = 0; i < n; ++i) h.nodes[i].y = depth[i];
}

size_t max_chunk_texels() {
  GLint max_texels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
  size_t limit = static_cast<size_t>(std::max(max_texels, 1));
  // OITBENCH_MAX_TEXEL_BUFFER lowers the limit, so the tests run the chunked path on small images.
  if (const char* env = std::getenv("OITBENCH_MAX_TEXEL_BUFFER"); env && *env) {
    char* end = nullptr;
    unsigned long long v = std::strtoull(env, &end, 10);
    if (*end || v == 0)
      throw std::invalid_argument(std::string("OITBENCH_MAX_TEXEL_BUFFER='") + env +
                                  "' is not a positive number of texels");
    limit = std::min<size_t>(limit, v);
  }
  return std::bit_floor(limit);
}

size_t chunks_for(size_t texels) {
  size_t chunk = max_chunk_texels();
  return std::max<size_t>(1, (texels + chunk - 1) / chunk);
}

GLuint chunk_unit(GLuint first_unit, ChunkSlot slot, size_t chunk) {
  if (chunk == 0) return first_unit;
  return CAPTURE_CHUNK_UNIT_BASE + static_cast<GLuint>((chunk - 1) * 3) + static_cast<GLuint>(slot);
}

Defines chunk_defines(size_t chunks, unsigned shift) {
  if (chunks <= 1) return {};
  return {{"FRAG_CHUNKS", std::to_string(chunks)}, {"FRAG_CHUNK_SHIFT", std::to_string(shift)}};
}

Defines FragmentStorage::node_defines() const {
  Defines d = frag_format_defines(format_);
  for (auto& x : chunk_defines(nodes_.chunks(), nodes_.shift())) d.push_back(x);
  return d;
}

size_t FragmentStorage::allocate_nodes(size_t pool, const std::string& what) {
  check_pool(pool);
  const size_t chunks = std::max(nodes_.chunks(), chunks_for(pool));
  nodes_ = NodePool(pool, format_.colour, what, chunks);
  pool_ = pool;
  return chunks;
}

ChunkedTexels::ChunkedTexels(size_t texels, GLenum format, size_t texel_bytes, const std::string& what,
                             size_t min_chunks)
    : format_(format), texel_bytes_(texel_bytes) {
  const size_t chunk = max_chunk_texels();
  shift_ = static_cast<unsigned>(std::countr_zero(chunk));
  const size_t chunks = std::max(chunks_for(texels), min_chunks);
  if (chunks > kMaxChunks)
    throw Unsupported(what + " of " + std::to_string(texels) + " fragments needs " + std::to_string(chunks) +
                      " texel buffers of GL_MAX_TEXTURE_BUFFER_SIZE (" + std::to_string(chunk) +
                      " texels); the storage binds at most " + std::to_string(kMaxChunks));
  for (size_t c = 0; c < chunks; ++c) {
    size_t first = c * chunk;
    size_t n = first < texels ? std::min(chunk, texels - first) : 1;  // a chunk kept for min_chunks: one texel
    buffers_.push_back(gl::make_buffer());
    views_.push_back(gl::make_texture(GL_TEXTURE_BUFFER));
    glNamedBufferStorage(buffers_.back().get(), static_cast<GLsizeiptr>(n * texel_bytes), nullptr, 0);
    glTextureBuffer(views_.back().get(), format, buffers_.back().get());
  }
}

void ChunkedTexels::bind(GLuint first_unit, ChunkSlot slot) const {
  for (size_t c = 0; c < views_.size(); ++c)
    glBindImageTexture(chunk_unit(first_unit, slot, c), views_[c].get(), 0, GL_FALSE, 0, GL_READ_WRITE, format_);
}

void ChunkedTexels::read(size_t n, void* out) const {
  auto* dst = static_cast<char*>(out);
  const size_t chunk = size_t{1} << shift_;
  for (size_t c = 0; c < buffers_.size() && c * chunk < n; ++c) {
    size_t count = std::min(chunk, n - c * chunk);
    glGetNamedBufferSubData(buffers_[c].get(), 0, static_cast<GLsizeiptr>(count * texel_bytes_),
                            dst + c * chunk * texel_bytes_);
  }
}

MemoryNeed fragment_memory(CaptureStorage kind, FragFormat format, bool with_counts, unsigned long long pool,
                           size_t pixels, int host_copies) {
  const bool lists = kind == CaptureStorage::PPLL;
  const size_t node = frag_node_bytes(format.colour) + (lists ? 4 : 0);  // PPLL: the next pointer
  const size_t gpu_pixel = lists ? 4 * (with_counts ? 2 : 1) : 4 * 3;    // heads (counts); counts, offsets, scan
  // Read back: nodes (8) and next (4), wide colours (16), the read's depth (4) and rgba16f's colours (8).
  const size_t host = format.colour == FragColour::RGBA8     ? 12
                      : format.colour == FragColour::RGBA16F ? 12 + 16 + 4 + 8
                                                             : 12 + 16 + 4;
  MemoryNeed need;
  need.gpu_bytes = pool * node + pixels * gpu_pixel;
  need.gpu_what = std::string(lists ? "the linked lists" : "the packed arrays") + " (a pool of " + format_count(pool) +
                  " fragments x " + std::to_string(node) + " B)";
  const unsigned long long copies = static_cast<unsigned long long>(std::max(host_copies, 1));
  need.cpu_bytes = copies * pool * host + pixels * kValidationBytesPerPixel;
  need.cpu_what = "the read-back and the references (" + (copies > 1 ? std::to_string(copies) + " x " : "") +
                  format_count(pool) + " fragments x " + std::to_string(host) + " B, " + format_count(pixels) +
                  " pixels x " + std::to_string(kValidationBytesPerPixel) + " B)";
  return need;
}

void require_fragment_budget(CaptureStorage kind, const CaseContext& ctx, bool with_counts, FragFormat format,
                             const FragmentBudget& budget) {
  if (budget.expected == 0) return;
  const size_t pixels = static_cast<size_t>(ctx.width()) * ctx.height();
  require_memory(
      combined(
          fragment_memory(kind, format, with_counts, budget.expected + budget.expected / 8, pixels, budget.host_copies),
          budget.held),
      ctx.memory(), "~" + format_count(budget.expected) + " fragments (estimated from the scene's primitives):");
  if (budget.expected >= kListEnd)
    throw Unsupported("~" + format_count(budget.expected) + " fragments (estimated from the scene's primitives): " +
                      "the capture indexes fragments with 32 bits (at most " + format_count(kListEnd - 1) + ")");
}

std::unique_ptr<FragmentStorage> make_fragment_storage(CaptureStorage kind, const CaseContext& ctx, size_t initial_pool,
                                                       bool with_counts, FragFormat format, FragmentBudget budget) {
  const size_t pixels = static_cast<size_t>(ctx.width()) * ctx.height();
  const MemoryLimits limits = ctx.memory();
  auto guard = [=](size_t pool) {
    require_memory(combined(fragment_memory(kind, format, with_counts, pool, pixels, budget.host_copies), budget.held),
                   limits, "a pool of " + format_count(pool) + " fragments");
  };
  // The scene's estimate first: nothing is allocated or drawn for a case that cannot be held.
  require_fragment_budget(kind, ctx, with_counts, format, budget);
  guard(initial_pool);
  std::unique_ptr<FragmentStorage> storage;
  if (kind == CaptureStorage::PPPA)
    storage = std::make_unique<PackedArrays>(ctx, initial_pool, format);
  else
    storage = std::make_unique<FragmentLists>(ctx.width(), ctx.height(), initial_pool, with_counts, format);
  storage->set_pool_guard(guard);
  return storage;
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

int capture_complete(FragmentStorage& storage, std::vector<gl::Program>& programs,
                     const std::function<std::vector<gl::Program>()>& build, const std::function<void()>& draw) {
  Defines built = storage.defines();
  int rerenders = storage.capture(ids(programs), draw);
  while (storage.defines() != built) {  // chunks only grow, to kMaxChunks (then Unsupported): this ends
    built = storage.defines();
    programs = build();
    rerenders += 1 + storage.capture(ids(programs), draw);
  }
  return rerenders;
}

}  // namespace oitbench::oit
