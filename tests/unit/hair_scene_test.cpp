// Hair as scene data: the strands generator makes line segments (Mesh::line_indices), one primitive
// per segment in the view's submission order; scenes/hair.json declares its light and effects.
#include <gtest/gtest.h>

#include <cmath>

#include "oit/scene/scene.hpp"

namespace oitbench::oit {
namespace {

float distance_to_eye(const Mesh& m, size_t segment, const View& v) {
  glm::vec3 mid =
      0.5f * (m.vertices[m.line_indices[2 * segment]].position + m.vertices[m.line_indices[2 * segment + 1]].position);
  return glm::length(mid - v.eye);
}

TEST(HairScene, LoadsWithItsLightEffectsAndSegmentCount) {
  SceneDesc s = load_scene("hair");
  EXPECT_EQ(s.effects, (std::vector<std::string>{"transparency", "self-shadowing"}));
  EXPECT_TRUE(s.has_effect("self-shadowing"));
  ASSERT_TRUE(s.light.has_value());
  EXPECT_GT(s.light->eye.y, 1.0f);  // above the head
  EXPECT_FLOAT_EQ(s.light->fov_deg, 50.0f);
  EXPECT_NO_THROW(s.view("fwd"));
  EXPECT_NO_THROW(s.view("rev"));

  Mesh full = build_mesh(s, s.view("fwd"), Detail::Full);
  EXPECT_EQ(full.segments(), 90000u);
  EXPECT_EQ(full.triangles(), 0u);
  EXPECT_EQ(full.polygons(), 90000u);  // polygons count line segments
  Mesh small = build_mesh(s, s.view("fwd"), Detail::Small);
  EXPECT_EQ(small.segments(), 6000u);
  for (unsigned i : small.line_indices) ASSERT_LT(i, small.vertices.size());
  // Every segment carries the material's alpha (float: the capture quantises it to its frag_colour).
  for (const auto& v : small.vertices) ASSERT_FLOAT_EQ(v.colour.a, 0.3f);
}

TEST(HairScene, StrandsAreConnectedWalksFromTheHead) {
  SceneDesc s = load_scene("hair");
  View as_generated = s.view("fwd");
  as_generated.order = SubmitOrder::AsGenerated;
  Mesh m = build_mesh(s, as_generated, Detail::Small);
  ASSERT_EQ(m.segments(), 6000u);
  const float head = 0.5f, step = 0.06f;
  for (size_t i = 0; i < m.segments(); ++i) {
    glm::vec3 a = m.vertices[m.line_indices[2 * i]].position, b = m.vertices[m.line_indices[2 * i + 1]].position;
    ASSERT_NEAR(glm::length(b - a), step, 1e-4f) << "segment " << i;
    if (i % 16 == 0) {
      ASSERT_NEAR(glm::length(a), head, 1e-4f) << "strand " << i / 16 << " starts on the head";
      ASSERT_GE(a.y, -0.3f * head - 1e-4f) << "no roots under the chin";
    } else {
      ASSERT_EQ(m.line_indices[2 * i], m.line_indices[2 * i - 1]) << "segment " << i << " continues its strand";
    }
  }
}

TEST(HairScene, SegmentsAreSubmittedInTheViewsOrder) {
  SceneDesc s = load_scene("hair");
  for (const char* name : {"fwd", "rev"}) {
    const View& v = s.view(name);
    Mesh m = build_mesh(s, v, Detail::Small);
    ASSERT_EQ(m.segments(), 6000u);
    for (size_t i = 1; i < m.segments(); ++i) {
      float before = distance_to_eye(m, i - 1, v), here = distance_to_eye(m, i, v);
      if (v.order == SubmitOrder::FrontToBack)
        ASSERT_LE(before, here + 1e-5f) << name << " segment " << i;
      else
        ASSERT_GE(before + 1e-5f, here) << name << " segment " << i;
    }
  }
}

TEST(HairScene, StrandParametersAreChecked) {
  auto error_of = [](const std::string& params) {
    try {
      parse_scene("h.json",
                  R"({"materials": {"x": {}}, "objects": [{"generator": "strands", "material": "x", "params": )" +
                      params + "}], \"views\": {\"v\": {\"eye\": [0, 0, 3]}}}");
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error_of(R"({"lowest_root": 2})").find("/objects/0/params/lowest_root: expected a number in [-1, 0.9]"),
            std::string::npos)
      << error_of(R"({"lowest_root": 2})");
  EXPECT_NE(error_of(R"({"per_strands": 8})").find("unknown key \"per_strands\""), std::string::npos);
  EXPECT_EQ(error_of(R"({"segments": 100, "per_strand": 8, "curl": 0.2, "lowest_root": -0.5})"), "");
  // The strands' own count and per-strand length: 100 segments in strands of 8 (the last one short).
  SceneDesc s = parse_scene(
      "h.json",
      R"({"materials": {"x": {}}, "objects": [{"generator": "strands", "material": "x", "params": {"segments": 100, "per_strand": 8}}], "views": {"v": {"eye": [0, 0, 3]}}})");
  EXPECT_EQ(build_mesh(s, s.views[0], Detail::Full).segments(), 100u);
  EXPECT_EQ(build_mesh(s, s.views[0], Detail::Full).vertices.size(), 100u + 13u);  // 13 strands, one root each
}

TEST(HairScene, StrandsAsTubesAreTheHairballsSurfaces) {
  const std::string text =
      R"({"materials": {"x": {}}, "objects": [{"generator": "strands", "material": "x", "params": {"segments": 50, "sides": SIDES}}], "views": {"v": {"eye": [0, 0, 3]}}})";
  auto with_sides = [&](const std::string& sides) {
    std::string t = text;
    t.replace(t.find("SIDES"), 5, sides);
    return t;
  };
  SceneDesc s = parse_scene("h.json", with_sides("3"));
  Mesh m = build_mesh(s, s.views[0], Detail::Full);
  EXPECT_EQ(m.segments(), 0u);
  EXPECT_EQ(m.triangles(), 50u * 3 * 2);  // a 3-sided open tube per step: 3 quads
  try {
    parse_scene("h.json", with_sides("2"));
    FAIL() << "2 sides";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("/objects/0/params/sides: expected 0 (line segments) or 3"), std::string::npos)
        << e.what();
  }
}

TEST(HairScene, SelfShadowingNeedsTheLight) {
  try {
    parse_scene("h.json", R"({"effects": ["transparency", "self-shadowing"], "materials": {"x": {}},
      "objects": [{"generator": "strands", "material": "x"}], "views": {"v": {"eye": [0, 0, 3]}}})");
    FAIL() << "no light";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("needs a light"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace oitbench::oit
