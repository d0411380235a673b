#include "oit/capture/packed_arrays.hpp"

#include <algorithm>
#include <chrono>
#include <string>

namespace oitbench::oit {

PackedArrays::PackedArrays(const CaseContext& ctx, size_t initial_pool, FragFormat format)
    : FragmentStorage(ctx.width(), ctx.height(), format),
      counts_(gl::make_texture(GL_TEXTURE_2D)),
      offsets_(gl::make_buffer()),
      scan_(ctx, static_cast<size_t>(ctx.width()) * ctx.height()) {
  glTextureStorage2D(counts_.get(), 1, GL_R32UI, width_, height_);
  glNamedBufferStorage(offsets_.get(),
                       static_cast<GLsizeiptr>(static_cast<size_t>(width_) * height_ * sizeof(unsigned)), nullptr, 0);
  allocate(std::max<size_t>(initial_pool, 1));
}

void PackedArrays::allocate(size_t pool) { allocate_nodes(pool, "packed per-pixel arrays"); }

void PackedArrays::bind() const {
  nodes_.bind();
  glBindImageTexture(kCountsUnit, counts_.get(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kOffsetsBinding, offsets_.get());
}

size_t PackedArrays::bytes() const {
  size_t pixels = static_cast<size_t>(width_) * height_;
  return pool_ * frag_node_bytes(format_.colour) + pixels * 4 * 2 +
         scan_.bytes();  // fragments, counts, offsets, the scan's levels
}

int PackedArrays::capture(const std::vector<GLuint>& programs, const std::function<void()>& draw) {
  const unsigned zero = 0;
  auto start = std::chrono::steady_clock::now();
  glClearTexImage(counts_.get(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  bind();
  glUseProgram(programs.at(0));
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  draw();
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  scan_.scan_counts(counts_.get(), offsets_.get());
  fragments_ = scan_.read_total();  // waits for the count pass and the scan
  last_count_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  // Sized before anything is stored, so nothing overflows: grown with 1/8 to spare, and brought
  // back within 1.1x of what is needed once a frame needs less.
  if (fragments_ > pool_)
    allocate(std::max<size_t>(fragments_ + fragments_ / 8, 1));
  else if (pool_ > fragments_ + fragments_ / 10)
    allocate(std::max<size_t>(fragments_ + fragments_ / 32, 1));
  bind();
  glUseProgram(programs.at(1));
  glUniform1ui(glGetUniformLocation(programs[1], "poolSize"), static_cast<GLuint>(pool_));
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  draw();
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  return 0;
}

HostLists PackedArrays::read_back() const {
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  HostLists h;
  h.width = width_;
  h.height = height_;
  const size_t pixels = static_cast<size_t>(width_) * height_;
  h.counts.resize(pixels);
  glGetTextureImage(counts_.get(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, static_cast<GLsizei>(pixels * 4),
                    h.counts.data());
  std::vector<unsigned> firsts(pixels);  // the fill counted each pixel's end down to its first slot
  glGetNamedBufferSubData(offsets_.get(), 0, static_cast<GLsizeiptr>(pixels * 4), firsts.data());
  const size_t n = std::min(fragments_, pool_);
  nodes_.read(n, h);
  // As lists: pixel p's fragments are the slots [first, first + count) of the scan, in that order
  // (the last to arrive first, as a linked list holds them).
  h.heads.assign(pixels, kListEnd);
  h.next.assign(n, kListEnd);
  size_t first = 0, wrong = 0;
  for (size_t p = 0; p < pixels; ++p) {
    const size_t end = first + h.counts[p];
    if (firsts[p] != first) {
      if (!wrong++)
        h.error = "pixel (" + std::to_string(p % width_) + "," + std::to_string(p / width_) + "): the fill stored " +
                  std::to_string(static_cast<long long>(end) - static_cast<long long>(firsts[p])) + " of its " +
                  std::to_string(h.counts[p]) + " counted fragments";
    }
    if (end > n) {  // the counts disagree with the scan's total: keep the lists inside the pool
      if (h.error.empty()) h.error = "the per-pixel counts add up to more than the scan's total";
      break;
    }
    if (h.counts[p]) h.heads[p] = static_cast<unsigned>(first);
    for (size_t i = first; i + 1 < end; ++i) h.next[i] = static_cast<unsigned>(i + 1);
    first = end;
  }
  if (wrong > 1) h.error += " (and " + std::to_string(wrong - 1) + " more pixel(s))";
  return h;
}

}  // namespace oitbench::oit
