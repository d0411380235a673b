// Splat scenes: the "splats" generator makes what its parameters say (count, clusters, anisotropy,
// opacity range), deterministically; scene files using it are checked like any other (FILE:LINE:COLUMN);
// its size is bounded before anything is allocated; splats count as primitives and order with the view.
#include "oit/splats/splat_scene.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

#include "oit/scene/scene.hpp"

namespace oitbench::oit {
namespace {

std::string splat_scene(const std::string& params, const std::string& small = "{}") {
  return R"({
  "materials": { "m": { "colour": [0.5, 0.5, 0.5], "alpha": 0.5 } },
  "objects": [ { "generator": "splats", "material": "m",
                 "params": )" +
         params + R"(,
                 "small": )" +
         small + R"( } ],
  "views": { "fwd": { "eye": [0, 0, 4], "order": "front-to-back" }, "gen": { "eye": [0, 0, 4] } }
})";
}

std::string error_of(const std::string& text, unsigned long long max_bytes = kMaxMeshBytes) {
  try {
    SceneDesc s = parse_scene("s.json", text);
    build_mesh(s, s.view("gen"), Detail::Full, false, max_bytes);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SplatScene, TheGeneratorMakesWhatItsParametersSay) {
  SceneDesc s = parse_scene("s.json", splat_scene(R"({"count": 5000, "clusters": 7, "anisotropy": 5,
      "scale_min": 0.01, "scale_max": 0.02, "opacity_min": 0.2, "opacity_max": 0.6, "seed": 3})"));
  Mesh m = build_mesh(s, s.view("gen"), Detail::Full);
  ASSERT_EQ(m.splats.size(), 5000u);
  EXPECT_EQ(m.polygons(), 5000u);  // the polygons metric counts splats
  EXPECT_TRUE(m.vertices.empty() && m.indices.empty());
  for (const Splat& sp : m.splats) {
    const float largest = std::max({sp.scale.x, sp.scale.y, sp.scale.z});
    const float smallest = std::min({sp.scale.x, sp.scale.y, sp.scale.z});
    EXPECT_NEAR(largest / smallest, 5.0f, 1e-3f);
    EXPECT_GE(largest, 0.01f - 1e-6f);
    EXPECT_LE(largest, 0.02f + 1e-6f);
    EXPECT_GE(sp.opacity, 0.2f);
    EXPECT_LE(sp.opacity, 0.6f);
    EXPECT_NEAR(glm::length(glm::vec4(sp.rotation.w, sp.rotation.x, sp.rotation.y, sp.rotation.z)), 1.0f, 1e-5f);
    for (int c = 0; c < 3; ++c) EXPECT_TRUE(sp.colour[c] >= 0 && sp.colour[c] <= 1);
  }
  // Seven clusters: splats come cluster by cluster, each cluster one colour family.
  Mesh again = build_mesh(s, s.view("gen"), Detail::Full);
  for (size_t i = 0; i < m.splats.size(); ++i) {
    ASSERT_EQ(m.splats[i].position, again.splats[i].position) << i;  // deterministic
    ASSERT_EQ(m.splats[i].colour, again.splats[i].colour) << i;
  }
  SceneDesc other = parse_scene("s.json", splat_scene(R"({"count": 5000, "seed": 4})"));
  EXPECT_NE(build_mesh(other, other.view("gen"), Detail::Full).splats[0].position, m.splats[0].position);
}

TEST(SplatScene, DepthAndOpacityShapeDoWhatTheySay) {
  auto mean_z_spread = [](const std::string& params) {
    SceneDesc s = parse_scene("s.json", splat_scene(params));
    Mesh m = build_mesh(s, s.view("gen"), Detail::Full);
    double lo = 1e9, hi = -1e9, opacity = 0;
    for (const Splat& sp : m.splats) {
      lo = std::min<double>(lo, sp.position.z);
      hi = std::max<double>(hi, sp.position.z);
      opacity += sp.opacity;
    }
    return std::pair<double, double>{hi - lo, opacity / m.splats.size()};
  };
  auto flat = mean_z_spread(R"({"count": 2000, "depth": 0, "spread": 0.01})");
  auto deep = mean_z_spread(R"({"count": 2000, "depth": 4, "spread": 0.01})");
  EXPECT_LT(flat.first, 0.1);
  EXPECT_GT(deep.first, 1.0);
  auto faint = mean_z_spread(R"({"count": 2000, "opacity_shape": 4})");
  EXPECT_LT(faint.second, flat.second - 0.2);  // u^4 favours opacity_min
}

TEST(SplatScene, SmallOverridesAndTheViewsOrder) {
  SceneDesc s = parse_scene("s.json", splat_scene(R"({"count": 3000})", R"({"count": 300})"));
  EXPECT_EQ(build_mesh(s, s.view("gen"), Detail::Small).splats.size(), 300u);
  Mesh m = build_mesh(s, s.view("fwd"), Detail::Full);
  for (size_t i = 1; i < m.splats.size(); ++i)
    ASSERT_LE(glm::length(m.splats[i - 1].position - s.view("fwd").eye),
              glm::length(m.splats[i].position - s.view("fwd").eye));
  // near_far encloses every splat's 3 standard deviations.
  glm::vec2 nf = near_far(s.view("fwd"), m);
  for (const Splat& sp : m.splats) {
    const float d = glm::length(sp.position - s.view("fwd").eye);
    ASSERT_GT(d, nf.x);
    ASSERT_LT(d, nf.y);
  }
}

TEST(SplatScene, BadParametersNameTheLineAndWhatIsWrong) {
  std::string e = error_of(splat_scene(R"({"opacity_min": 0.9, "opacity_max": 0.5})"));
  EXPECT_NE(e.find("s.json:4:"), std::string::npos) << e;  // the line of "params"' opacity_min
  EXPECT_NE(e.find("/objects/0/params/opacity_min: opacity_min is above opacity_max"), std::string::npos) << e;
  e = error_of(splat_scene(R"({"scale_max": 0.001})"));  // below the default scale_min
  EXPECT_NE(e.find("/objects/0/params: scale_min is above scale_max (with the defaults"), std::string::npos) << e;
  e = error_of(splat_scene("{}", R"({"anisotropy": 0.5})"));
  EXPECT_NE(e.find("/objects/0/small/anisotropy: expected a number in [1, "), std::string::npos) << e;
  e = error_of(splat_scene(R"({"opacity_max": 2})"));
  EXPECT_NE(e.find("/objects/0/params/opacity_max: expected a number in [0, 1]"), std::string::npos) << e;
  e = error_of(splat_scene(R"({"count": 1.5})"));
  EXPECT_NE(e.find("expected a whole number"), std::string::npos) << e;
  e = error_of(splat_scene(R"({"scale_min": 0})"));
  EXPECT_NE(e.find("expected a number above 0"), std::string::npos) << e;
  e = error_of(R"({"materials": {"m": {}}, "objects": [{"generator": "ply", "material": "m"}],
                   "views": {"gen": {"eye": [0, 0, 3]}}})");
  EXPECT_NE(e.find("expected \"file\": the 3DGS PLY file"), std::string::npos) << e;
}

TEST(SplatScene, TenMillionSplatsAreBoundedBeforeAnythingIsAllocated) {
  auto t0 = std::chrono::steady_clock::now();
  std::string e = error_of(splat_scene(R"({"count": 10000000})"), 1ull << 30);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 1.0);
  EXPECT_NE(e.find("s.json: /objects/0 (splats): count 1e+07 makes the mesh about 1e+07 primitives (1e+07 splats)"),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("the most oitbench builds is 1 GiB"), std::string::npos) << e;
  // Past the parser's bound for counts.
  e = error_of(splat_scene(R"({"count": 20000000})"));
  EXPECT_NE(e.find("/objects/0/params/count: expected a number in [0, 1e+07]"), std::string::npos) << e;
}

TEST(SplatScene, EffectsSeeSplatsAsTransparent) {
  std::string text = splat_scene(R"({"count": 10})");
  text.insert(1, R"("effects": ["transparency"],)");
  EXPECT_NO_THROW(parse_scene("s.json", text));
}

}  // namespace
}  // namespace oitbench::oit
