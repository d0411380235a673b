#include "viewer/depth_complexity.hpp"

#include <array>

#include "gl/gl.hpp"
#include "oit/capture/fragment_storage.hpp"
#include "shaders/viewer/bindings.h"

namespace oitbench::viewer {

DepthComplexity::DepthComplexity(const ShaderLibrary& shaders)
    : shaders_(shaders),
      colour_(shaders.build(
          {{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "viewer/depth_colour.frag"}}, {})),
      stats_(gl::make_buffer()) {
  glNamedBufferStorage(stats_.get(), 2 * sizeof(unsigned), nullptr, GL_DYNAMIC_STORAGE_BIT);
}

DepthComplexity::Counts DepthComplexity::count(const oit::FragmentStorage& lists, const Defines& storage_defines,
                                               int width, int height) {
  if (!count_ || storage_defines != count_defines_) {
    count_ = shaders_.build({{GL_COMPUTE_SHADER, "viewer/depth_count.comp"}}, storage_defines);
    count_defines_ = storage_defines;
  }
  if (width != width_ || height != height_) {
    counts_ = gl::make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(counts_.get(), 1, GL_R32UI, width, height);
    width_ = width;
    height_ = height;
  }
  const std::array<unsigned, 2> zero{0, 0};
  glNamedBufferSubData(stats_.get(), 0, sizeof zero, zero.data());
  lists.bind();
  glBindImageTexture(DEPTH_COUNTS_UNIT, counts_.get(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DEPTH_STATS_BINDING, stats_.get());
  glUseProgram(count_.get());
  glDispatchCompute((width + 7) / 8, (height + 7) / 8, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  std::array<unsigned, 2> stats{};
  glGetNamedBufferSubData(stats_.get(), 0, sizeof stats, stats.data());
  return {stats[0], stats[1]};
}

void DepthComplexity::draw(int fb_width, int fb_height) const {
  if (!counts_) return;
  glUseProgram(colour_.get());
  glUniform2f(glGetUniformLocation(colour_.get(), "texelsPerPixel"), static_cast<float>(width_) / fb_width,
              static_cast<float>(height_) / fb_height);
  glBindImageTexture(DEPTH_COUNTS_UNIT, counts_.get(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DEPTH_STATS_BINDING, stats_.get());
  triangle_.draw();
}

}  // namespace oitbench::viewer
