#include "oit/scene/radix_sort.hpp"

#include <algorithm>

#include "shaders/lines/bindings.h"

namespace oitbench::oit {

namespace {

gl::Buffer storage(size_t bytes) {
  gl::Buffer b = gl::make_buffer();
  glNamedBufferStorage(b.get(), static_cast<GLsizeiptr>(std::max<size_t>(bytes, 4)), nullptr, 0);
  return b;
}

}  // namespace

RadixSort::RadixSort(const CaseContext& ctx, size_t count, int bits) : count_(count), bits_(bits) {
  const size_t n = count * sizeof(unsigned);
  for (auto* b : {&keys0_, &index0_, &keys_[0], &keys_[1], &index_[0], &index_[1], &local_}) *b = storage(n);
  blocks_ = storage((count / 256 + 2) * sizeof(unsigned));
  for (const char* phase : {"PHASE_LOCAL", "PHASE_BLOCKS", "PHASE_SCATTER"})
    split_.push_back(ctx.build({{GL_COMPUTE_SHADER, "lines/split.comp"}}, {{phase, ""}}));
}

size_t RadixSort::bytes_for(size_t count) { return (7 * count + count / 256 + 2) * sizeof(unsigned); }

void RadixSort::sort() const {
  const GLuint count = static_cast<GLuint>(count_), groups = (count + 255) / 256;
  for (int bit = 0; bit < bits_; ++bit) {
    const gl::Buffer& kin = bit == 0 ? keys0_ : keys_[(bit + 1) % 2];
    const gl::Buffer& iin = bit == 0 ? index0_ : index_[(bit + 1) % 2];
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SPLIT_KEYS_IN_BINDING, kin.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SPLIT_INDICES_IN_BINDING, iin.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SPLIT_KEYS_OUT_BINDING, keys_[bit % 2].get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SPLIT_INDICES_OUT_BINDING, index_[bit % 2].get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SPLIT_LOCAL_BINDING, local_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SPLIT_BLOCKS_BINDING, blocks_.get());
    for (size_t phase = 0; phase < split_.size(); ++phase) {
      glUseProgram(split_[phase].get());
      glUniform1ui(glGetUniformLocation(split_[phase].get(), "count"), count);
      glUniform1ui(glGetUniformLocation(split_[phase].get(), "bit"), static_cast<GLuint>(bit));
      glDispatchCompute(phase == 1 ? 1 : groups, 1, 1);
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
  }
}

}  // namespace oitbench::oit
