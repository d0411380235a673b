#pragma once
// Packed per-pixel arrays, PPPA (Knowles 2014 section 2.2, after Peeper's linearized A-buffer;
// shaders/capture/packed_arrays.glsl): a count pass of the geometry, an inclusive prefix sum of
// the per-pixel counts (prefix_sum.hpp) whose total sizes the fragment buffer before anything is
// stored, and a fill pass that puts each fragment in its pixel's last free slot (so each pixel
// holds its fragments in the order its linked list would: the last to arrive first). No next pointers (a
// fragment's 8 bytes instead of 12 in RGBA8), no global counter to contend on, never an overflow: the price
// is the second pass of the geometry. The counts stay, so BMA needs nothing more.
#include "oit/capture/fragment_storage.hpp"
#include "oit/capture/prefix_sum.hpp"

namespace oitbench::oit {

class PackedArrays final : public FragmentStorage {
 public:
  PackedArrays(const CaseContext& ctx, size_t initial_pool, FragFormat format = {});

  CaptureStorage kind() const override { return CaptureStorage::PPPA; }
  Defines defines() const override {
    Defines d = node_defines();
    d.push_back({"STORAGE_PPPA", ""});
    return d;
  }
  std::vector<Defines> capture_passes() const override {
    return {{{"STORAGE_PPPA_COUNT", ""}}, {{"STORAGE_PPPA_FILL", ""}}};
  }
  // programs[0] counts, then the scan sizes the buffer (within 1.25x of the fragments), then
  // programs[1] fills. Never re-renders: returns 0.
  int capture(const std::vector<GLuint>& programs, const std::function<void()>& draw) override;
  void bind() const override;
  size_t bytes() const override;
  bool with_counts() const override { return true; }
  // Also checks that the fill ended each pixel where the scan said (every counted fragment
  // stored, no pixel spilling into the next): HostLists::error names the first pixel that did not.
  HostLists read_back() const override;
  // CPU time of the last capture's count pass and prefix sum (up to the total on the CPU), ms.
  double last_count_ms() const { return last_count_ms_; }

 private:
  void allocate(size_t pool);
  gl::Texture counts_;
  gl::Buffer offsets_;
  PrefixSum scan_;
  double last_count_ms_ = 0;
};

}  // namespace oitbench::oit
