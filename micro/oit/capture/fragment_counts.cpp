#include "oit/capture/fragment_counts.hpp"

#include <algorithm>

namespace oitbench::oit {

std::vector<unsigned> FragmentCounts::depths() const {
  std::vector<bool> seen(static_cast<size_t>(peak_depth) + 1, false);
  for (unsigned d : depth) seen[d] = true;
  std::vector<unsigned> out;
  for (unsigned d = 1; d <= peak_depth; ++d)
    if (seen[d]) out.push_back(d);
  return out;
}

FragmentCounter::FragmentCounter(const CaseContext& ctx, const std::vector<ShaderStage>& stages, FragFormat format,
                                 const Defines& extra)
    : width_(ctx.width()), height_(ctx.height()), counts_(gl::make_texture(GL_TEXTURE_2D)) {
  Defines d = frag_format_defines(format);
  d.insert(d.end(), {{"STORAGE_PPPA", ""}, {"STORAGE_PPPA_COUNT", ""}});
  d.insert(d.end(), extra.begin(), extra.end());
  program_ = ctx.build(stages, d);
  glTextureStorage2D(counts_.get(), 1, GL_R32UI, width_, height_);
}

FragmentCounts FragmentCounter::count(const std::function<void()>& draw) const {
  const unsigned zero = 0;
  glClearTexImage(counts_.get(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  glBindImageTexture(kCountsUnit, counts_.get(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
  glUseProgram(program_.get());
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  draw();
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
  FragmentCounts c;
  const size_t pixels = static_cast<size_t>(width_) * height_;
  c.depth.resize(pixels);
  glGetTextureImage(counts_.get(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, static_cast<GLsizei>(pixels * 4),
                    c.depth.data());
  for (unsigned d : c.depth) {
    c.peak_depth = std::max(c.peak_depth, d);
    c.total_fragments += d;
  }
  return c;
}

}  // namespace oitbench::oit
