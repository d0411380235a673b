#include "oit/storage/storage_layout.hpp"

#include <cstdio>
#include <stdexcept>

#include "core/registry.hpp"
#include "shaders/storage/bindings.h"

namespace oitbench {

namespace {
int groups_per_row(int width, int group_x) { return (width + group_x - 1) / group_x; }
}  // namespace

StorageLayout StorageLayout::parse(const std::string& name) {
  StorageLayout l;
  if (name == "ssbo") return l;
  if (name == "texture3d") {
    l.kind = Kind::Texture3d;
    return l;
  }
  if (name == "texbuffer") {
    l.kind = Kind::TexBuffer;
    return l;
  }
  int gx = 0, gy = 0, a = 0;
  char tail = 0;
  if (std::sscanf(name.c_str(), "interleaved-%dx%d-a%d%c", &gx, &gy, &a, &tail) == 3 && gx > 0 && gy > 0 && a > 0) {
    l.kind = Kind::Interleaved;
    l.group_x = gx;
    l.group_y = gy;
    l.align = a;
    return l;
  }
  throw std::invalid_argument("unknown storage layout '" + name +
                              "' (ssbo, texture3d, texbuffer or interleaved-GXxGY-aA, e.g. interleaved-2x4-a1)");
}

std::vector<std::string> StorageLayout::names() {
  std::vector<std::string> n = {"ssbo", "texture3d", "texbuffer"};
  for (int a : {1, 4})
    for (const char* g : {"1x1", "2x2", "2x4", "4x2", "4x4", "8x8"})
      n.push_back(std::string("interleaved-") + g + "-a" + std::to_string(a));
  return n;
}

std::string StorageLayout::name() const {
  switch (kind) {
    case Kind::Ssbo:
      return "ssbo";
    case Kind::Texture3d:
      return "texture3d";
    case Kind::TexBuffer:
      return "texbuffer";
    case Kind::Interleaved:
      break;
  }
  return "interleaved-" + std::to_string(group_x) + "x" + std::to_string(group_y) + "-a" + std::to_string(align);
}

Defines StorageLayout::defines(int width, int height, int nodes) const {
  static constexpr const char* kinds[] = {"STORAGE_SSBO", "STORAGE_TEXTURE3D", "STORAGE_INTERLEAVED",
                                          "STORAGE_TEXBUFFER"};
  Defines d = {{kinds[static_cast<int>(kind)], ""},
               {"STORAGE_WIDTH", std::to_string(width)},
               {"STORAGE_HEIGHT", std::to_string(height)},
               {"STORAGE_NODES", std::to_string(nodes)}};
  if (kind == Kind::Interleaved) {
    d.push_back({"STORAGE_GROUP_X", std::to_string(group_x)});
    d.push_back({"STORAGE_GROUP_Y", std::to_string(group_y)});
    d.push_back({"STORAGE_ALIGN", std::to_string(align)});
  }
  return d;
}

std::size_t StorageLayout::node_capacity(int width, int height, int nodes) const {
  if (kind != Kind::Interleaved) return static_cast<std::size_t>(width) * height * nodes;
  std::size_t groups = static_cast<std::size_t>(groups_per_row(width, group_x)) * ((height + group_y - 1) / group_y);
  return groups * group_x * group_y * nodes;
}

std::size_t StorageLayout::index(int x, int y, int i, int width, int nodes) const {
  if (kind != Kind::Interleaved) return (static_cast<std::size_t>(y) * width + x) * nodes + i;
  // Eq. 4.2, nodes kept in runs of `align` (align 1 is the equation as printed).
  std::size_t stride = static_cast<std::size_t>(group_x) * group_y;
  std::size_t gID = static_cast<std::size_t>(y / group_y) * groups_per_row(width, group_x) + x / group_x;
  std::size_t gOffset = gID * nodes * stride;
  std::size_t localID = static_cast<std::size_t>(y % group_y) * group_x + x % group_x;
  std::size_t run = static_cast<std::size_t>(i / align);
  return gOffset + (run * stride + localID) * align + i % align;
}

StorageResources::StorageResources(const StorageLayout& layout, int width, int height, int nodes)
    : layout_(layout), width_(width), height_(height), nodes_(nodes) {
  if (layout.kind == StorageLayout::Kind::Interleaved && nodes % layout.align != 0)
    throw std::invalid_argument(layout.name() + ": nodes (" + std::to_string(nodes) +
                                ") must be a multiple of the alignment");
  std::size_t count = layout.node_capacity(width, height, nodes);
  if (layout.kind == StorageLayout::Kind::Texture3d) {
    GLint max3d = 0;
    glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &max3d);
    if (width > max3d || height > max3d || nodes > max3d)
      throw Unsupported("texture3d " + std::to_string(width) + "x" + std::to_string(height) + "x" +
                        std::to_string(nodes) + " exceeds GL_MAX_3D_TEXTURE_SIZE " + std::to_string(max3d));
    texture_ = gl::make_texture(GL_TEXTURE_3D);
    glTextureStorage3D(texture_.get(), 1, GL_RG32UI, width, height, nodes);
    return;
  }
  GLint64 max_block = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
  std::size_t bytes = count * sizeof(StorageNode);
  if (static_cast<GLint64>(bytes) > max_block)
    throw Unsupported(layout.name() + ": " + std::to_string(bytes) + " bytes exceed GL_MAX_SHADER_STORAGE_BLOCK_SIZE " +
                      std::to_string(max_block));
  buffer_ = gl::make_buffer();
  glNamedBufferStorage(buffer_.get(), static_cast<GLsizeiptr>(bytes), nullptr, GL_DYNAMIC_STORAGE_BIT);
  if (layout.kind == StorageLayout::Kind::TexBuffer) {
    GLint max_texels = 0;
    glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
    if (count > static_cast<std::size_t>(max_texels))
      throw Unsupported("texbuffer: " + std::to_string(count) + " texels exceed GL_MAX_TEXTURE_BUFFER_SIZE " +
                        std::to_string(max_texels));
    texture_ = gl::make_texture(GL_TEXTURE_BUFFER);
    glTextureBuffer(texture_.get(), GL_RG32UI, buffer_.get());
  }
}

void StorageResources::clear() const {
  if (layout_.kind == StorageLayout::Kind::Texture3d)
    glClearTexImage(texture_.get(), 0, GL_RG_INTEGER, GL_UNSIGNED_INT, nullptr);
  else
    glClearNamedBufferData(buffer_.get(), GL_RG32UI, GL_RG_INTEGER, GL_UNSIGNED_INT, nullptr);
}

void StorageResources::bind() const {
  if (layout_.kind == StorageLayout::Kind::Texture3d) {
    glBindImageTexture(STORAGE_IMAGE_UNIT, texture_.get(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_RG32UI);
    return;
  }
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, STORAGE_BUFFER_BINDING, buffer_.get());
  if (layout_.kind == StorageLayout::Kind::TexBuffer) glBindTextureUnit(STORAGE_READ_TEXTURE_UNIT, texture_.get());
}

std::vector<StorageNode> StorageResources::read_back() const {
  std::size_t pixels = static_cast<std::size_t>(width_) * height_;
  std::vector<StorageNode> out(pixels * nodes_);
  glMemoryBarrier(GL_ALL_BARRIER_BITS);
  if (layout_.kind == StorageLayout::Kind::Texture3d) {
    // The image is x-fastest, then y, then the node slice: transpose into pixel-major order.
    std::vector<StorageNode> slices(out.size());
    glGetTextureImage(texture_.get(), 0, GL_RG_INTEGER, GL_UNSIGNED_INT,
                      static_cast<GLsizei>(slices.size() * sizeof(StorageNode)), slices.data());
    for (int i = 0; i < nodes_; ++i)
      for (std::size_t p = 0; p < pixels; ++p) out[p * nodes_ + i] = slices[i * pixels + p];
    return out;
  }
  std::vector<StorageNode> raw(layout_.node_capacity(width_, height_, nodes_));
  glGetNamedBufferSubData(buffer_.get(), 0, static_cast<GLsizeiptr>(raw.size() * sizeof(StorageNode)), raw.data());
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x)
      for (int i = 0; i < nodes_; ++i)
        out[(static_cast<std::size_t>(y) * width_ + x) * nodes_ + i] = raw[layout_.index(x, y, i, width_, nodes_)];
  return out;
}

gl::Framebuffer storage_only_framebuffer(int width, int height) {
  auto fbo = gl::make_framebuffer();
  glNamedFramebufferParameteri(fbo.get(), GL_FRAMEBUFFER_DEFAULT_WIDTH, width);
  glNamedFramebufferParameteri(fbo.get(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, height);
  return fbo;
}

void StorageResources::barrier() {
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

}  // namespace oitbench
