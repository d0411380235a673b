// The analytic splat reference (micro/oit/splats/splat_reference.*): one isotropic splat against its
// closed form, the projection's Jacobian against the perspective map's finite differences, two splats
// whose centre order and ray-maximum order differ (the global-sort model differs from the exact
// reference there), the tiles against a brute-force compositor, determinism, early termination.
#include "oit/splats/splat_reference.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "oit/splats/splat_scene.hpp"

namespace oitbench::oit {
namespace {

View front_view() {
  View v;
  v.eye = glm::vec3(0, 0, 4);
  v.target = glm::vec3(0, 0, 0);
  v.up = glm::vec3(0, 1, 0);
  v.fov_deg = 40;
  return v;
}

TEST(SplatReference, OneIsotropicSplatIsItsClosedForm) {
  const SplatCamera cam = splat_camera(front_view(), 64, 48, 0.1);
  Splat s;
  s.scale = glm::vec3(0.05f);
  s.opacity = 0.8f;
  s.colour = glm::vec3(0.2f, 0.4f, 0.9f);
  SplatReferenceOptions o;
  o.background = glm::dvec3(1.0, 0.5, 0.0);
  const SplatImage img = splat_reference({s}, cam, o);
  const double f = 48 / (2 * std::tan(glm::radians(20.0))), t = 4.0;
  const double sigma = 0.05f, opacity = 0.8f;                  // the float values the splat holds
  const double var = (f * sigma / t) * (f * sigma / t) + 0.3;  // (f σ / t)² + the low-pass
  const int radius = static_cast<int>(std::ceil(3 * std::sqrt(var)));
  const auto p = project_splat(s, cam);
  ASSERT_TRUE(p);
  EXPECT_EQ(p->radius, radius);
  EXPECT_DOUBLE_EQ(p->centre_depth, 4.0);
  int covered = 0;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) {
      const double dx = x + 0.5 - 32, dy = y + 0.5 - 24;
      double alpha = std::min(0.99, opacity * std::exp(-0.5 * (dx * dx + dy * dy) / var));
      if (alpha < 1 / 255.0 || std::abs(dx) >= radius || std::abs(dy) >= radius) alpha = 0;
      covered += alpha > 0;
      const glm::dvec3 expected = alpha * glm::dvec3(s.colour) + (1 - alpha) * o.background;
      const glm::dvec4 got = img.at(x, y);
      for (int k = 0; k < 3; ++k) ASSERT_NEAR(got[k], expected[k], 1e-12) << x << "," << y;
      ASSERT_NEAR(got.a, alpha, 1e-12);
      ASSERT_EQ(img.fragments[static_cast<size_t>(y) * 64 + x], alpha > 0 ? 1u : 0u);
      // A sphere's maximum along a ray is the ray's point nearest its centre: s* = v.μ / v.v.
      const glm::dvec3 v(dx / f, dy / f, -1), mu(0, 0, -4);
      EXPECT_NEAR(ray_max_depth(*p, {x + 0.5, y + 0.5}, cam), glm::dot(v, mu) / glm::dot(v, v), 1e-12);
    }
  EXPECT_GT(covered, 20);
  // With RGBA8 fragments: each fragment's alpha and colour rounded to 8 bits first.
  o.quantise_rgba8 = true;
  const SplatImage q = splat_reference({s}, cam, o);
  auto unorm8 = [](double v) { return std::round(v * 255) / 255; };
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) {
      const double a = img.at(x, y).a, qa = unorm8(a);
      for (int k = 0; k < 3; ++k)
        ASSERT_NEAR(q.at(x, y)[k], qa * unorm8(s.colour[k]) + (1 - qa) * o.background[k], 1e-12) << x << "," << y;
      ASSERT_NEAR(q.at(x, y).a, qa, 1e-12);
    }
  o.quantise_rgba8 = false;
  // Outside the near and far planes: skipped.
  EXPECT_FALSE(project_splat(s, splat_camera(front_view(), 64, 48, 4.0)));
  EXPECT_FALSE(project_splat(s, splat_camera(front_view(), 64, 48, 0.1, 3.9)));
  EXPECT_TRUE(project_splat(s, splat_camera(front_view(), 64, 48, 3.9, 4.1)));
  // A rotation changes nothing but rounding (the rotation is float).
  s.rotation = glm::normalize(glm::quat(0.3f, 0.5f, -0.2f, 0.7f));
  const SplatImage turned = splat_reference({s}, cam, o);
  for (size_t i = 0; i < img.rgba.size(); ++i) ASSERT_NEAR(glm::length(turned.rgba[i] - img.rgba[i]), 0.0, 1e-6);
}

// The 2D covariance is the perspective map's linearisation at the centre: J from finite differences.
TEST(SplatReference, TheJacobianIsThePerspectivesDerivative) {
  View v = front_view();
  v.eye = glm::vec3(1.0f, 0.5f, 4.0f);
  v.target = glm::vec3(0.3f, -0.2f, 0.0f);
  const SplatCamera cam = splat_camera(v, 128, 96, 0.1);
  Splat s;
  s.position = glm::vec3(-0.4f, 0.3f, 0.2f);  // off the axis: x / t and y / t well away from 0
  s.scale = glm::vec3(0.3f, 0.02f, 0.08f);
  s.rotation = glm::normalize(glm::quat(0.8f, 0.1f, 0.5f, -0.3f));
  const auto p = project_splat(s, cam);
  ASSERT_TRUE(p);
  const glm::dvec3 mu = cam.rotation * glm::dvec3(s.position) + cam.translation;
  auto project = [&](glm::dvec3 q) { return glm::dvec2(cam.cx + cam.fx * q.x / -q.z, cam.cy + cam.fy * q.y / -q.z); };
  double j[2][3];
  for (int k = 0; k < 3; ++k) {
    glm::dvec3 h(0.0);
    h[k] = 1e-6;
    const glm::dvec2 d = (project(mu + h) - project(mu - h)) / 2e-6;
    j[0][k] = d.x;
    j[1][k] = d.y;
  }
  const glm::dmat3 r =
      cam.rotation * glm::mat3_cast(glm::dquat(s.rotation.w, s.rotation.x, s.rotation.y, s.rotation.z));
  const glm::dvec3 sd(s.scale);
  const glm::dmat3 cov = r * glm::dmat3(sd.x * sd.x, 0, 0, 0, sd.y * sd.y, 0, 0, 0, sd.z * sd.z) * glm::transpose(r);
  double c2[2][2] = {};
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) c2[a][b] += j[a][k] * cov[l][k] * j[b][l];
  const double xx = c2[0][0] + 0.3, xy = c2[0][1], yy = c2[1][1] + 0.3, det = xx * yy - xy * xy;
  EXPECT_NEAR(p->conic.x, yy / det, 1e-6 * std::abs(yy / det));
  EXPECT_NEAR(p->conic.y, -xy / det, 1e-6 * std::abs(xy / det));
  EXPECT_NEAR(p->conic.z, xx / det, 1e-6 * std::abs(xx / det));
  EXPECT_NEAR(p->mean.x, project(mu).x, 1e-9);
  EXPECT_NEAR(p->mean.y, project(mu).y, 1e-9);
}

// A: a long thin red splat tilted into depth; B: a small blue one whose centre is nearer than A's,
// but behind A's ridge along B's rays. The global sort puts B first; the exact reference puts A first.
TEST(SplatReference, CentreOrderAndRayMaximumOrderDiffer) {
  const SplatCamera cam = splat_camera(front_view(), 64, 64, 0.1);
  Splat a, b;
  a.scale = glm::vec3(1.0f, 0.05f, 0.05f);
  a.rotation = glm::angleAxis(glm::radians(45.0f), glm::vec3(0, 1, 0));  // local x to (1, 0, -1) / sqrt 2
  a.opacity = 0.95f;
  a.colour = glm::vec3(1, 0, 0);
  b.position = glm::vec3(-0.3f, 0.0f, 0.1f);
  b.scale = glm::vec3(0.05f);
  b.opacity = 0.95f;
  b.colour = glm::vec3(0, 0, 1);
  const auto pa = project_splat(a, cam), pb = project_splat(b, cam);
  ASSERT_TRUE(pa && pb);
  EXPECT_LT(pb->centre_depth, pa->centre_depth);
  const glm::dvec2 at(std::floor(pb->mean.x) + 0.5, std::floor(pb->mean.y) + 0.5);
  EXPECT_LT(ray_max_depth(*pa, at, cam), ray_max_depth(*pb, at, cam));
  SplatReferenceOptions exact, global;
  global.order = SplatOrder::Centre;
  const SplatImage e = splat_reference({a, b}, cam, exact), g = splat_reference({a, b}, cam, global);
  const int x = static_cast<int>(at.x), y = static_cast<int>(at.y);
  EXPECT_EQ(e.fragments[static_cast<size_t>(y) * 64 + x], 2u);
  EXPECT_GT(e.at(x, y).r, e.at(x, y).b);  // red in front
  EXPECT_GT(g.at(x, y).b, g.at(x, y).r);  // blue in front
  // Where only one splat reaches, both agree.
  int differ = 0, same = 0;
  for (size_t i = 0; i < e.rgba.size(); ++i) {
    const double d = glm::length(e.rgba[i] - g.rgba[i]);
    if (e.fragments[i] < 2) {
      EXPECT_EQ(d, 0.0);
    }
    (d > 0.1 ? differ : same) += 1;
  }
  EXPECT_GT(differ, 0);
  EXPECT_GT(same, differ);
}

// The tiles change nothing: every pixel as a brute-force loop over all splats composites it.
TEST(SplatReference, TilesAgreeWithBruteForceAndRunsRepeat) {
  SplatGeneratorParams gp;
  gp.count = 3000;
  gp.clusters = 5;
  gp.depth = 1.5;
  gp.scale_min = 0.02;
  gp.scale_max = 0.12;
  gp.anisotropy = 6;
  Material m;
  const SplatList splats = generate_splats(gp, m);
  const SplatCamera cam = splat_camera(front_view(), 40, 36, 0.5);
  for (SplatOrder order : {SplatOrder::RayMaximum, SplatOrder::Centre}) {
    SplatReferenceOptions o;
    o.order = order;
    const SplatImage img = splat_reference(splats, cam, o);
    o.threads = 1;
    const SplatImage again = splat_reference(splats, cam, o);  // one worker: the same image, bit for bit
    o.threads = 3;
    const SplatImage third = splat_reference(splats, cam, o);
    ASSERT_TRUE(img.rgba == again.rgba && img.fragments == again.fragments);
    ASSERT_TRUE(img.rgba == third.rgba && img.fragments == third.fragments);
    std::vector<std::optional<SplatProjection>> proj;
    for (const Splat& s : splats) proj.push_back(project_splat(s, cam));
    size_t deep = 0;
    for (int y = 0; y < 36; ++y)
      for (int x = 0; x < 40; ++x) {
        const glm::dvec2 c(x + 0.5, y + 0.5);
        std::vector<std::tuple<double, size_t, double>> frags;
        for (size_t i = 0; i < splats.size(); ++i) {
          if (!proj[i]) continue;
          const double alpha = splat_alpha(*proj[i], c);
          if (alpha > 0)
            frags.emplace_back(order == SplatOrder::Centre ? proj[i]->centre_depth : ray_max_depth(*proj[i], c, cam), i,
                               alpha);
        }
        std::sort(frags.begin(), frags.end());
        glm::dvec3 col(0.0);
        double t = 1;
        for (const auto& [key, i, alpha] : frags) {
          col += t * alpha * glm::dvec3(splats[i].colour);
          t *= 1 - alpha;
        }
        col += t * o.background;
        ASSERT_EQ(img.fragments[static_cast<size_t>(y) * 40 + x], frags.size());
        for (int k = 0; k < 3; ++k) ASSERT_NEAR(img.at(x, y)[k], col[k], 1e-12) << x << "," << y;
        deep += frags.size() > 10;
      }
    EXPECT_GT(deep, 100u);  // the scene overlaps: the orders matter
  }
}

TEST(SplatReference, EarlyTerminationStopsBeforeTheTransmittanceFallsBelowIt) {
  const SplatCamera cam = splat_camera(front_view(), 16, 16, 0.1);
  SplatList s(3);
  for (int i = 0; i < 3; ++i) {
    s[i].position = glm::vec3(0, 0, 0.1f * i);  // the last is the nearest
    s[i].scale = glm::vec3(0.5f);
    s[i].opacity = 1.0f;  // alpha 0.99 at the centre
    s[i].colour = glm::vec3(i == 2, i == 1, i == 0);
  }
  SplatReferenceOptions o;
  o.background = glm::dvec3(0.0);
  o.min_transmittance = 1e-3;  // after the nearest T = 0.01, after the next 1e-4: stop before it
  const glm::dvec4 c = splat_reference(s, cam, o).at(8, 8);
  EXPECT_GT(c.a, 0.95);
  EXPECT_NEAR(c.r, c.a, 1e-12);  // the nearest alone
  EXPECT_EQ(c.g, 0.0);
  o.min_transmittance = 0;
  EXPECT_GT(splat_reference(s, cam, o).at(8, 8).g, 0.005);
}

}  // namespace
}  // namespace oitbench::oit
