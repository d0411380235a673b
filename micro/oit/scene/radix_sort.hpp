#pragma once
// The stream-split radix sort of (key, index) pairs on the GPU (Sintorn et al.'s hair poster;
// shaders/lines/split.comp: one bit a round, each round a count, a prefix sum and a stable scatter),
// written once for every primitive sort: the lines experiment's segments, the self-shadowing map's
// slices (shadow_map.cpp) and the splats' global sort (GLOBAL-SORT, micro/oit/approx/approx_case.cpp).
// The caller fills keys_in() and indices_in() (size() uints each) and calls sort(); the sorted pairs
// are then in sorted_keys() and sorted_indices(), ascending by key, equal keys in their input order.
#include <cstddef>
#include <vector>

#include "core/registry.hpp"
#include "gl/gl_objects.hpp"
#include "gl/shader.hpp"

namespace oitbench::oit {

class RadixSort {
 public:
  // `count` pairs, keys of `bits` bits (the rounds: a key's higher bits are ignored).
  RadixSort(const CaseContext& ctx, size_t count, int bits);
  void sort() const;
  size_t size() const { return count_; }
  int bits() const { return bits_; }
  const gl::Buffer& keys_in() const { return keys0_; }
  const gl::Buffer& indices_in() const { return index0_; }
  const gl::Buffer& sorted_keys() const { return bits_ == 0 ? keys0_ : keys_[(bits_ - 1) % 2]; }
  const gl::Buffer& sorted_indices() const { return bits_ == 0 ? index0_ : index_[(bits_ - 1) % 2]; }
  size_t bytes() const { return bytes_for(count_); }  // GPU memory of its buffers
  static size_t bytes_for(size_t count);              // a sort of `count` pairs' buffers, before it is made

 private:
  size_t count_;
  int bits_;
  gl::Buffer keys0_, index0_, keys_[2], index_[2], local_, blocks_;
  std::vector<gl::Program> split_;  // PHASE_LOCAL, PHASE_BLOCKS, PHASE_SCATTER
};

}  // namespace oitbench::oit
