#pragma once
// Per-pixel linked lists of fragments (Yang et al. 2010, the capture every resolve here shares):
// a global atomic counter allocates nodes, imageAtomicExchange on r32ui head pointers links them,
// nodes are uvec2 (packed RGBA8 colour, depth bits) with next pointers in a parallel buffer.
// The node pool is sized from the previous frame's count; a frame whose counter passes the pool is
// rendered again with a bigger pool (counted, never truncated). BMA also counts fragments per pixel.
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "core/gl_objects.hpp"

namespace oitbench::oit {

inline constexpr unsigned kListEnd = 0xFFFFFFFFu;

// Image units and bindings shared with shaders/oit/storage/linked_list.glsl.
inline constexpr GLuint kHeadsUnit = 0, kNodesUnit = 1, kNextUnit = 2, kCountsUnit = 3, kCounterBinding = 0;

// The lists as read back to the CPU (the input of the CPU reference and of CPU-NATIVE).
struct HostLists {
  int width = 0, height = 0;
  std::vector<unsigned> heads;     // width*height, row-major from the bottom row
  std::vector<glm::uvec2> nodes;   // (packUnorm4x8 colour, floatBitsToUint depth)
  std::vector<unsigned> next;
  std::vector<unsigned> counts;    // per-pixel counts when captured with counts, else empty
};

class FragmentLists {
 public:
  FragmentLists(int width, int height, size_t initial_pool, bool with_counts);

  // Clears the heads (and counts), binds everything, calls `draw` with `program` current, and
  // re-renders with a bigger pool while the counter passed the pool. Returns the re-renders.
  int capture(GLuint program, const std::function<void()>& draw);
  void bind() const;  // images for a resolve pass
  size_t fragments() const { return fragments_; }
  size_t pool() const { return pool_; }
  bool with_counts() const { return with_counts_; }
  HostLists read_back() const;

 private:
  void allocate(size_t pool);
  int width_, height_;
  bool with_counts_;
  size_t pool_ = 0, fragments_ = 0, shrink_to_ = 0;  // shrink_to_: the next capture's pool (0: keep)
  GLint max_texels_ = 0;
  gl::Texture heads_, counts_, nodes_view_, next_view_;
  gl::Buffer nodes_, next_, counter_;
};

}  // namespace oitbench::oit
