#include "oit/capture/prefix_sum.hpp"

#include <string>

#include "shaders/capture/bindings.h"

namespace oitbench::oit {

namespace {
constexpr size_t kBlock = 1024;  // SCAN_BLOCK in shaders/capture/prefix_sum.comp: 256 invocations x 4
constexpr GLuint kInBinding = SCAN_IN_BINDING, kOutBinding = SCAN_OUT_BINDING, kSumsBinding = SCAN_BLOCK_SUMS_BINDING,
                 kCountsUnit = SCAN_COUNTS_UNIT;

void set_count(GLuint program, size_t n) {
  glProgramUniform1ui(program, glGetUniformLocation(program, "count"), static_cast<GLuint>(n));
}
}  // namespace

PrefixSum::PrefixSum(const CaseContext& ctx, size_t count)
    : count_(count),
      from_counts_(ctx.build({{GL_COMPUTE_SHADER, "capture/prefix_sum.comp"}},
                             {{"SCAN_BLOCKS", ""}, {"SCAN_FROM_COUNTS", ""}, {"SCAN_INCLUSIVE", ""}})),
      from_buffer_(ctx.build({{GL_COMPUTE_SHADER, "capture/prefix_sum.comp"}}, {{"SCAN_BLOCKS", ""}})),
      add_(ctx.build({{GL_COMPUTE_SHADER, "capture/prefix_sum.comp"}}, {{"SCAN_ADD", ""}})) {
  GLint max_groups = 0;
  glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 0, &max_groups);
  if ((count + kBlock - 1) / kBlock > static_cast<size_t>(max_groups))
    throw Unsupported("a prefix sum of " + std::to_string(count) +
                      " elements needs more than GL_MAX_COMPUTE_WORK_GROUP_COUNT (" + std::to_string(max_groups) +
                      ") groups of " + std::to_string(kBlock));
  sizes_.push_back(std::max<size_t>(count, 1));
  do {
    sizes_.push_back((sizes_.back() + kBlock - 1) / kBlock);
    levels_.push_back(gl::make_buffer());
    glNamedBufferStorage(levels_.back().get(), static_cast<GLsizeiptr>(sizes_.back() * sizeof(unsigned)), nullptr, 0);
  } while (sizes_.back() > 1);
}

void PrefixSum::scan_counts(GLuint counts_texture, GLuint out) const { scan(counts_texture, 0, out); }
void PrefixSum::scan_buffer(GLuint in, GLuint out) const { scan(0, in, out); }

void PrefixSum::scan(GLuint counts_texture, GLuint in, GLuint out) const {
  // Up: each level's blocks scanned, their totals one level up; the last level is one total.
  for (size_t k = 0; k + 1 < sizes_.size(); ++k) {
    GLuint level_in = k == 0 ? in : levels_[k - 1].get(), level_out = k == 0 ? out : levels_[k - 1].get();
    const gl::Program& prog = k == 0 && counts_texture ? from_counts_ : from_buffer_;
    set_count(prog.get(), k == 0 ? count_ : sizes_[k]);
    glUseProgram(prog.get());
    if (k == 0 && counts_texture)
      glBindImageTexture(kCountsUnit, counts_texture, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);
    else
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kInBinding, level_in);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kOutBinding, level_out);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kSumsBinding, levels_[k].get());
    glDispatchCompute(static_cast<GLuint>(sizes_[k + 1]), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }
  // Down: a level whose totals filled more than one block adds their scanned values to its blocks.
  for (size_t k = sizes_.size() - 2; k-- > 0;) {
    GLuint level_out = k == 0 ? out : levels_[k - 1].get();
    set_count(add_.get(), k == 0 ? count_ : sizes_[k]);
    glUseProgram(add_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kOutBinding, level_out);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kSumsBinding, levels_[k].get());
    glDispatchCompute(static_cast<GLuint>(sizes_[k + 1]), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }
}

unsigned PrefixSum::read_total() const {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  unsigned total = 0;
  glGetNamedBufferSubData(levels_.back().get(), 0, sizeof total, &total);
  return total;
}

size_t PrefixSum::bytes() const {
  size_t b = 0;
  for (size_t k = 1; k < sizes_.size(); ++k) b += sizes_[k] * sizeof(unsigned);
  return b;
}

}  // namespace oitbench::oit
