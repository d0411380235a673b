#include "oit/resolve/compute_resolve.hpp"

#include <regex>
#include <stdexcept>

namespace oitbench::oit {

ComputeResolve::ComputeResolve(const CaseContext& ctx, Defines defines, glm::vec3 background, int group_x, int group_y)
    : group_x_(group_x), group_y_(group_y) {
  defines.push_back({"CS_GROUP_X", std::to_string(group_x)});
  defines.push_back({"CS_GROUP_Y", std::to_string(group_y)});
  program_ = ctx.build({{GL_COMPUTE_SHADER, "resolve/resolve.comp"}}, defines);
  glProgramUniform3f(program_.get(), glGetUniformLocation(program_.get(), "background"), background.r, background.g,
                     background.b);
  glProgramUniform1i(program_.get(), glGetUniformLocation(program_.get(), "zero"), 0);
}

void ComputeResolve::run(const FragmentStorage& lists, const RenderTarget& target) const {
  const float clear[4] = {0, 0, 0, 0};
  glClearNamedFramebufferfv(target.framebuffer(), GL_COLOR, 0, clear);
  lists.bind();
  glBindImageTexture(kResolvedUnit, target.color_texture(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glUseProgram(program_.get());
  glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  glDispatchCompute(static_cast<GLuint>((target.width() + group_x_ - 1) / group_x_),
                    static_cast<GLuint>((target.height() + group_y_ - 1) / group_y_), 1);
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

std::pair<int, int> parse_group(const std::string& text) {
  static const std::regex re(R"((\d{1,4})x(\d{1,4}))");
  std::smatch m;
  if (!std::regex_match(text, m, re)) throw std::invalid_argument("work group '" + text + "': expected XxY, e.g. 8x1");
  return {std::stoi(m[1]), std::stoi(m[2])};
}

}  // namespace oitbench::oit
