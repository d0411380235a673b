#pragma once
// Per-pixel node storage on the C++ side (Brüll 2018, section 4.1): which layout a case uses,
// the defines that select the matching include under shaders/storage/, the GL objects behind it,
// and a CPU copy of each layout's index equation so read-back does not trust the shader's own.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "gl/gl_objects.hpp"
#include "gl/shader.hpp"

namespace oitbench {

using StorageNode = std::array<std::uint32_t, 2>;  // uvec2, as STORAGE_NODE in shaders/storage/api.glsl

struct StorageLayout {
  enum class Kind { Ssbo, Texture3d, Interleaved, TexBuffer };
  Kind kind = Kind::Ssbo;
  int group_x = 1, group_y = 1, align = 1;  // interleaved only

  // "ssbo", "texture3d", "texbuffer", "interleaved-GXxGY-aA" (e.g. interleaved-2x4-a4).
  static StorageLayout parse(const std::string& name);
  // The layouts the layout experiment compares: the thesis's three plus the buffer-texture read
  // path, and interleaved groups 1x1..8x8 with node alignment 1 and 4.
  static std::vector<std::string> names();
  std::string name() const;

  // STORAGE_<KIND>, STORAGE_WIDTH/HEIGHT/NODES (+ group and alignment): for CaseContext::build.
  Defines defines(int width, int height, int nodes) const;
  // Nodes the layout allocates (interleaved rounds the screen up to whole groups).
  std::size_t node_capacity(int width, int height, int nodes) const;
  // Eq. 4.1 / Eq. 4.2 (with alignment) on the CPU; texture3d is addressed by (x, y, i) directly.
  std::size_t index(int x, int y, int i, int width, int nodes) const;
};

// The GL objects of one layout for a w x h screen with n nodes per pixel.
class StorageResources {
 public:
  // Throws Unsupported when the driver cannot hold it (buffer-texture or SSBO size limits).
  StorageResources(const StorageLayout& layout, int width, int height, int nodes);
  void clear() const;  // every node to (0, 0)
  void bind() const;   // binds to the points in shaders/storage/bindings.h
  // Every node in pixel-major order ((y * w + x) * n + i), whatever the layout.
  std::vector<StorageNode> read_back() const;
  // Makes this pass's writes visible to the next pass's reads (any access path).
  static void barrier();

 private:
  StorageLayout layout_;
  int width_, height_, nodes_;
  gl::Buffer buffer_;
  gl::Texture texture_;  // texture3d: the storage; texbuffer: the read view of buffer_
};

// A framebuffer without attachments for passes whose only output is the storage (rasterises a
// width x height screen, writes no colour).
gl::Framebuffer storage_only_framebuffer(int width, int height);

}  // namespace oitbench
