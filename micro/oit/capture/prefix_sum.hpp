#pragma once
// A prefix sum on the GPU (shaders/capture/prefix_sum.comp): blocks of 1024 elements scanned
// by one work group each, their totals scanned the same way one level up, until one block holds
// everything, then each level's scanned totals added back down. PPPA's capture uses it to turn the
// per-pixel counts into each pixel's end, one past its last slot (packed_arrays.hpp).
#include <cstddef>
#include <vector>

#include "core/registry.hpp"
#include "gl/gl_objects.hpp"

namespace oitbench::oit {

class PrefixSum {
 public:
  // Scans of `count` elements; throws Unsupported past the driver's work-group count.
  PrefixSum(const CaseContext& ctx, size_t count);

  // out[i] = counts[0] + ... + counts[i] (inclusive) over the r32ui counts texture in row-major
  // order (its width * height must be `count`); `out` holds `count` uints. Leaves the total on the GPU.
  void scan_counts(GLuint counts_texture, GLuint out) const;
  // out[i] = in[0] + ... + in[i-1] (exclusive) from a buffer of `count` uints (in may be out).
  void scan_buffer(GLuint in, GLuint out) const;
  // The sum of all elements of the last scan (waits for it).
  unsigned read_total() const;
  size_t bytes() const;  // the level buffers

 private:
  void scan(GLuint counts_texture, GLuint in, GLuint out) const;
  size_t count_;
  gl::Program from_counts_, from_buffer_, add_;
  std::vector<size_t> sizes_;       // elements per level: count, then block totals, ..., 1
  std::vector<gl::Buffer> levels_;  // levels_[k] holds the block totals of level k (sizes_[k + 1])
};

}  // namespace oitbench::oit
