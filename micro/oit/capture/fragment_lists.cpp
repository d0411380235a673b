#include "oit/capture/fragment_lists.hpp"

#include <algorithm>
#include <string>
#include <utility>

#include "core/registry.hpp"

namespace oitbench::oit {

FragmentLists::FragmentLists(int width, int height, size_t initial_pool, bool with_counts, FragFormat format)
    : FragmentStorage(width, height, format),
      with_counts_(with_counts),
      heads_(gl::make_texture(GL_TEXTURE_2D)),
      counter_(gl::make_buffer()) {
  glTextureStorage2D(heads_.get(), 1, GL_R32UI, width, height);
  if (with_counts) {
    counts_ = gl::make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(counts_.get(), 1, GL_R32UI, width, height);
  }
  glNamedBufferStorage(counter_.get(), sizeof(unsigned), nullptr, GL_DYNAMIC_STORAGE_BIT);
  allocate(std::max<size_t>(initial_pool, 1));
}

void FragmentLists::allocate(size_t pool) {
  size_t chunks = allocate_nodes(pool, "linked-list node pool");
  next_ = ChunkedTexels(pool, GL_R32UI, 4, "linked-list node pool", chunks);
}

Defines FragmentLists::defines() const { return node_defines(); }

void FragmentLists::bind() const {
  glBindImageTexture(kHeadsUnit, heads_.get(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
  nodes_.bind();
  next_.bind(kNextUnit, ChunkSlot::Next);
  if (with_counts_) glBindImageTexture(kCountsUnit, counts_.get(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
  glBindBufferBase(GL_ATOMIC_COUNTER_BUFFER, kCounterBinding, counter_.get());
}

std::vector<Defines> FragmentLists::capture_passes() const {
  if (with_counts_) return {{{"STORAGE_COUNTS", ""}}};
  return {{}};
}

size_t FragmentLists::bytes() const {
  // Nodes (the format's fragment + 4-byte next), the heads (and counts), the counter.
  size_t pixels = static_cast<size_t>(width_) * height_;
  return pool_ * (frag_node_bytes(format_.colour) + 4) + pixels * 4 * (with_counts_ ? 2 : 1) + sizeof(unsigned);
}

int FragmentLists::capture(const std::vector<GLuint>& programs, const std::function<void()>& draw) {
  const GLuint program = programs.at(0);
  int rerenders = 0;
  const unsigned end = kListEnd, zero = 0;
  // Shrinking happens before a frame, never after one: the lists just captured live in the pool.
  if (shrink_to_) allocate(std::exchange(shrink_to_, 0));
  for (;;) {
    glClearTexImage(heads_.get(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &end);
    if (with_counts_) glClearTexImage(counts_.get(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glNamedBufferSubData(counter_.get(), 0, sizeof(unsigned), &zero);
    bind();
    glUseProgram(program);
    glUniform1ui(glGetUniformLocation(program, "poolSize"), static_cast<GLuint>(pool_));
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_ATOMIC_COUNTER_BARRIER_BIT);
    draw();
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    unsigned count = 0;
    glGetNamedBufferSubData(counter_.get(), 0, sizeof(unsigned), &count);  // waits for the capture
    fragments_ = count;
    if (count <= pool_) {
      // Steady state: keep the pool within 1.1x of what the frame needed (sized from this count).
      if (pool_ > count + count / 10 && count > 0) shrink_to_ = count + count / 32;
      break;
    }
    // Overflowed: nodes past the pool were not written (nor linked); render the frame again, with
    // 1/8 to spare (the next frame brings it back within 1.1x).
    ++rerenders;
    allocate(count + count / 8 + 1);
  }
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  return rerenders;
}

HostLists FragmentLists::read_back() const {
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  HostLists h;
  h.width = width_;
  h.height = height_;
  size_t pixels = static_cast<size_t>(width_) * height_;
  h.heads.resize(pixels);
  glGetTextureImage(heads_.get(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, static_cast<GLsizei>(pixels * 4), h.heads.data());
  if (with_counts_) {
    h.counts.resize(pixels);
    glGetTextureImage(counts_.get(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, static_cast<GLsizei>(pixels * 4),
                      h.counts.data());
  }
  size_t n = std::min(fragments_, pool_);
  nodes_.read(n, h);
  h.next.resize(n);
  next_.read(n, h.next.data());
  return h;
}

}  // namespace oitbench::oit
