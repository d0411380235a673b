// The reference capture the separately validated cases share (visible_capture.hpp).
#include "oit/reference/visible_capture.hpp"

#include "gl/render_target.hpp"
#include "oit/case_support.hpp"
#include "oit/scene/coverage_estimate.hpp"
#include "oit/scene/scene_passes.hpp"
#include "oit/techniques.hpp"

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

std::string reference_view_key(const ParamSet& p, const CaseContext& ctx) {
  std::string key = std::to_string(ctx.width()) + "x" + std::to_string(ctx.height());
  for (const auto& [k, v] : p.values())
    if (k == "capture" || (k != "technique" && techniques_reading(k).empty())) key += " " + k + "=" + v;
  return key;
}

std::shared_ptr<const ReferenceView> reference_view(ScenePasses& fx, const glm::mat4& view_proj, const ParamSet& p,
                                                    CaseContext& ctx) {
  auto make = [&] {
    auto r = std::make_shared<ReferenceView>();
    VisibleFragments seen = capture_visible_fragments(fx, view_proj, p, ctx);
    r->backdrop = std::move(seen.backdrop);
    r->host = std::move(seen.host);
    r->hidden = seen.hidden;
    r->stats = list_stats(r->host);
    r->composite = composite_reference(r->host, r->backdrop);
    return std::shared_ptr<const ReferenceView>(std::move(r));
  };
  if (!ctx.shared()) return make();
  // Kept beside the live cases' own: a few views up to 256x256 (the reference runs' sizes; a preset's
  // requests visit the same scenes one technique after another, so a view comes back after the others'),
  // one above, where a view's fragments are big (a pool of them per pixel: ~13 M at 512x512 on the hairball).
  const size_t pixels = static_cast<size_t>(ctx.width()) * ctx.height();
  return ctx.shared()->get<ReferenceView>(reference_view_key(p, ctx), make, pixels <= 256 * 256 ? 4 : 1);
}

}  // namespace oitbench::oit
