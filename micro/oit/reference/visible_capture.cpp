// The reference capture the separately validated cases share (visible_capture.hpp).
#include "oit/reference/visible_capture.hpp"

#include "gl/render_target.hpp"
#include "oit/case_support.hpp"
#include "oit/scene/coverage_estimate.hpp"
#include "oit/scene/scene_passes.hpp"

namespace oitbench::oit {

VisibleFragments capture_visible_fragments(ScenePasses& fx, const glm::mat4& view_proj, const ParamSet& p,
                                           CaseContext& ctx) {
  VisibleFragments v;
  fx.draw_opaque();
  v.backdrop = fx.read_backdrop();
  const size_t pixels = static_cast<size_t>(ctx.width()) * ctx.height();
  auto lists = make_fragment_storage(parse_capture_storage(p.get("capture")), ctx, pixels * 4, false, {},
                                     capture_budget(fx.mesh(), view_proj, ctx, fx.opaque() ? 2 : 1));
  auto build = [&] {
    auto programs = build_capture_programs(
        *lists, ctx, {{GL_VERTEX_SHADER, "scene/scene.vert"}, {GL_FRAGMENT_SHADER, "capture/capture.frag"}},
        fx.geometry_defines());
    for (const auto& prog : programs) {
      set_view_proj(prog, view_proj);
      fx.bind_geometry(prog.get());
    }
    return programs;
  };
  auto capture = build();
  // Colour writes are off: the target only gives the capture the view's size.
  RenderTarget target(ctx.width(), ctx.height(), GL_R8);
  target.bind();
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  capture_complete(*lists, capture, build, [&] { fx.transparent().draw(); });
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  v.host = visible_fragments(lists->read_back(), v.backdrop, v.hidden);
  return v;
}

}  // namespace oitbench::oit
