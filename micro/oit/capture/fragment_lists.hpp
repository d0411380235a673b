#pragma once
// Per-pixel linked lists, PPLL (Yang et al. 2010; shaders/capture/fragment_lists.glsl): a global
// atomic counter allocates nodes, imageAtomicExchange on r32ui head pointers links them, nodes are
// the fragment format's words (uvec2 packed RGBA8 colour, depth bits by default) with next pointers in a parallel
// buffer. The node pool is sized from the previous frame's count; a frame whose counter passes the pool is rendered
// again with a bigger pool (counted, never truncated). BMA also counts fragments per pixel.
#include "oit/capture/fragment_storage.hpp"

namespace oitbench::oit {

class FragmentLists final : public FragmentStorage {
 public:
  FragmentLists(int width, int height, size_t initial_pool, bool with_counts, FragFormat format = {});

  CaptureStorage kind() const override { return CaptureStorage::PPLL; }
  Defines defines() const override;  // the format's, and the chunks' past one chunk
  std::vector<Defines> capture_passes() const override;
  // Clears the heads (and counts), binds everything, calls `draw` with programs[0] current, and
  // re-renders with a bigger pool while the counter passed the pool.
  int capture(const std::vector<GLuint>& programs, const std::function<void()>& draw) override;
  void bind() const override;
  size_t bytes() const override;
  bool with_counts() const override { return with_counts_; }
  HostLists read_back() const override;

 private:
  void allocate(size_t pool);
  bool with_counts_;
  size_t shrink_to_ = 0;  // pool for the next frame when this one needed much less
  gl::Texture heads_, counts_;
  ChunkedTexels next_;
  gl::Buffer counter_;
};

}  // namespace oitbench::oit
