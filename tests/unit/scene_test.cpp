// Scene files: the shipped scenes load and generate what they promise; broken files give an error
// naming the file, the line and column, and what was expected.
#include "oit/scene/scene.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

namespace oitbench::oit {
namespace {

std::string error_of(const std::string& text) {
  try {
    parse_scene("s.json", text);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

const char* kMinimal = R"({
  "materials": { "glass": { "colour": [1, 0, 0], "alpha": 0.5 } },
  "objects": [ { "generator": "planes", "material": "glass", "params": { "count": 4 } } ],
  "views": { "fwd": { "eye": [0, 0, 3] } }
})";

TEST(Scene, ShippedScenesLoadWithTheirViews) {
  for (const char* name : {"planes", "hairball", "hair", "smoke"}) {
    SceneDesc s = load_scene(name);
    EXPECT_EQ(s.name, name);
    EXPECT_NO_THROW(s.view("fwd"));
    EXPECT_NO_THROW(s.view("rev"));
    Mesh m = build_mesh(s, s.view("fwd"), Detail::Small);
    EXPECT_GT(m.polygons(), 0u) << name;
  }
  SceneDesc planes = load_scene("planes");
  EXPECT_EQ(build_mesh(planes, planes.view("fwd"), Detail::Full).polygons(), 2u * 128u);
  EXPECT_EQ(build_mesh(planes, planes.view("fwd"), Detail::Small).polygons(), 2u * 24u);
}

TEST(Scene, SubmitOrderFollowsTheView) {
  SceneDesc s = parse_scene("s.json", kMinimal);
  View v = s.view("fwd");
  for (auto order : {SubmitOrder::FrontToBack, SubmitOrder::BackToFront}) {
    v.order = order;
    Mesh m = build_mesh(s, v, Detail::Full);
    float first = m.vertices[m.indices.front()].position.z, last = m.vertices[m.indices.back()].position.z;
    if (order == SubmitOrder::FrontToBack)
      EXPECT_GT(first, last);  // the eye is at +z
    else
      EXPECT_LT(first, last);
  }
}

TEST(Scene, MalformedJsonNamesLineAndColumn) {
  std::string msg = error_of("{\n  \"materials\": {\n    \"glass\": { \"alpha\": 0.5, }\n  }\n}\n");
  EXPECT_EQ(msg.rfind("s.json:3:", 0), 0u) << msg;
  EXPECT_NE(msg.find("malformed JSON"), std::string::npos) << msg;
}

TEST(Scene, SemanticErrorsNameTheLineAndWhatWasExpected) {
  std::string text = kMinimal;
  std::string bad_alpha = text;
  bad_alpha.replace(bad_alpha.find("0.5"), 3, "1.5");
  std::string msg = error_of(bad_alpha);
  EXPECT_EQ(msg.rfind("s.json:2:", 0), 0u) << msg;
  EXPECT_NE(msg.find("/materials/glass/alpha: expected a number in [0, 1]"), std::string::npos) << msg;

  std::string bad_material = text;
  bad_material.replace(bad_material.find("\"material\": \"glass\""), 19, "\"material\": \"steel\"");
  msg = error_of(bad_material);
  EXPECT_EQ(msg.rfind("s.json:3:", 0), 0u) << msg;
  EXPECT_NE(msg.find("no material named \"steel\""), std::string::npos) << msg;

  std::string typo = text;
  typo.replace(typo.find("\"eye\""), 5, "\"eyes\"");
  msg = error_of(typo);
  EXPECT_EQ(msg.rfind("s.json:4:", 0), 0u) << msg;
  EXPECT_NE(msg.find("unknown key \"eyes\""), std::string::npos) << msg;

  msg = error_of(R"({"materials": {}, "objects": [{"generator": "teapot", "material": "x"}], "views": {}})");
  EXPECT_NE(msg.find("unknown generator \"teapot\""), std::string::npos) << msg;
}

TEST(Scene, EffectsAreCheckedAgainstWhatTheSceneHolds) {
  auto with = [](const std::string& effects, const std::string& extra = "", bool opaque = false) {
    return std::string("{\n  \"effects\": ") + effects + ",\n" + extra +
           "  \"materials\": { \"glass\": { \"alpha\": 0.5 }, \"wall\": { \"opaque\": " + (opaque ? "true" : "false") +
           " } },\n  \"objects\": [ { \"generator\": \"planes\", \"material\": \"glass\" },\n" +
           "               { \"generator\": \"planes\", \"material\": \"wall\" } ],\n" +
           "  \"views\": { \"fwd\": { \"eye\": [0, 0, 3] } }\n}";
  };
  std::string msg = error_of(with("[\"transparency\", \"fog\"]"));
  EXPECT_EQ(msg.rfind("s.json:2:", 0), 0u) << msg;
  EXPECT_NE(msg.find("unknown effect \"fog\"; valid effects: opaque, transparency, self-shadowing"), std::string::npos)
      << msg;
  msg = error_of(with("[\"opaque\", \"transparency\"]"));  // no opaque material
  EXPECT_EQ(msg.rfind("s.json:2:", 0), 0u) << msg;
  EXPECT_NE(msg.find("effect \"opaque\" has nothing to act on"), std::string::npos) << msg;
  msg = error_of(with("[\"transparency\", \"self-shadowing\"]"));
  EXPECT_NE(msg.find("effect \"self-shadowing\" needs a light"), std::string::npos) << msg;
  msg = error_of(with("[\"transparency\", \"transparency\"]"));
  EXPECT_NE(msg.find("declared twice"), std::string::npos) << msg;
  msg = error_of(with("[\"transparency\"]", "  \"light\": { \"eye\": [0, 3, 0], \"up\": [0, 1, 0] },\n"));
  EXPECT_EQ(msg.rfind("s.json:3:", 0), 0u) << msg;
  EXPECT_NE(msg.find("parallel to the light's direction"), std::string::npos) << msg;

  SceneDesc s = parse_scene("s.json", with("[\"transparency\", \"opaque\"]", "", true));
  EXPECT_EQ(s.effects, (std::vector<std::string>{"opaque", "transparency"}));  // canonical order
  EXPECT_TRUE(s.has_effect("opaque"));
  EXPECT_FALSE(s.light.has_value());
  Mesh split = build_mesh(s, s.view("fwd"), Detail::Full, true);
  Mesh together = build_mesh(s, s.view("fwd"), Detail::Full, false);
  EXPECT_EQ(split.opaque_indices.size(), split.indices.size());  // two equal stacks of planes
  EXPECT_TRUE(together.opaque_indices.empty());
  EXPECT_EQ(together.indices.size(), split.indices.size() + split.opaque_indices.size());
  EXPECT_EQ(load_scene("planes").effects, (std::vector<std::string>{"transparency"}));
}

TEST(Scene, EveryShippedSceneDeclaresItsEffects) {
  for (const auto& entry : std::filesystem::directory_iterator(default_scene_dir())) {
    if (entry.path().extension() != ".json") continue;
    std::ifstream in(entry.path());
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_NE(text.str().find("\"effects\""), std::string::npos) << entry.path() << " declares no effects";
    SceneDesc s = load_scene(entry.path().string());
    EXPECT_FALSE(s.effects.empty()) << entry.path();
  }
  EXPECT_EQ(load_scene("house-opaque").effects, (std::vector<std::string>{"opaque", "transparency"}));
}

TEST(Scene, ModelScenesLoadThroughAssimp) {
  for (const char* name : {"engine-grid", "house"}) {
    SceneDesc s = load_scene(name);
    Mesh m = build_mesh(s, s.views.front(), Detail::Small);
    EXPECT_GT(m.polygons(), 1000u) << name;
  }
}

// The power plant's stand-in: 3 x 5 x 7 engines of 121,496 triangles (12.76 M), three views.
TEST(Scene, EngineGridIsTheSpecifiedGrid) {
  SceneDesc s = load_scene("engine-grid");
  ASSERT_EQ(s.objects.size(), 1u);
  EXPECT_EQ(s.objects[0].params["grid"], nlohmann::json::array({3, 5, 7}));
  std::vector<std::string> views;
  for (const auto& v : s.views) views.push_back(v.name);
  EXPECT_EQ(views, (std::vector<std::string>{"V1", "V2", "V3"}));
  // One engine, then the small 1 x 2 x 2 grid: polygons scale with the instances.
  SceneDesc one = s;
  one.objects[0].params["grid"] = 1;
  size_t engine = build_mesh(one, s.views[0], Detail::Full).polygons();
  EXPECT_EQ(engine, 121496u);
  EXPECT_EQ(build_mesh(s, s.views[0], Detail::Small).polygons(), 4 * engine);
  // Every model material is transparent, each with its own alpha.
  Mesh m = build_mesh(one, s.views[0], Detail::Full);
  std::set<float> alphas;
  for (const auto& v : m.vertices) alphas.insert(v.colour.a);
  EXPECT_GE(alphas.size(), 6u);
  EXPECT_LT(*alphas.rbegin(), 1.0f);
}

// The atrium's stand-in: the site slab ("Erde") is dropped and the glass keeps the file's opacity 0.12.
TEST(Scene, HouseDropsTheSiteAndKeepsTheGlass) {
  SceneDesc s = load_scene("house");
  Mesh m = build_mesh(s, s.views.front(), Detail::Full);
  size_t glass = 0;
  for (const auto& v : m.vertices) glass += std::abs(v.colour.a - 0.12f) < 1e-6f;
  EXPECT_GT(glass, 0u);
  SceneDesc with_site = s;
  with_site.objects[0].params.erase("exclude_materials");
  EXPECT_EQ(build_mesh(with_site, s.views.front(), Detail::Full).polygons(), m.polygons() + 48);  // 4 slabs x 12
}

TEST(Scene, ModelParametersAreChecked) {
  auto error_of = [](const std::string& params) {
    try {
      parse_scene(
          "m.json",
          R"({"materials": {"x": {}}, "objects": [{"generator": "model", "file": "a.glb", "material": "x", "params": )" +
              params + "}], \"views\": {\"v\": {\"eye\": [0, 0, 3]}}}");
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error_of(R"({"grid": [3, 5]})").find("expected an array of 3 numbers"), std::string::npos);
  EXPECT_NE(error_of(R"({"alpha_by_material": {"Glas": 2}})").find("expected a number in [0, 1]"), std::string::npos);
  EXPECT_NE(error_of(R"({"exclude_materials": "Erde"})").find("expected an array of model material names"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"model_opacity": 1})").find("expected true or false"), std::string::npos);
  EXPECT_EQ(
      error_of(R"({"grid": [3, 5, 7], "spacing": 1.5, "alpha_by_material": {"A": 0.5}, "exclude_materials": ["B"]})"),
      "");
}

TEST(Scene, UnknownSceneListsTheScenes) {
  try {
    load_scene("no-such-scene");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("planes"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace oitbench::oit

namespace oitbench::oit {
namespace {

// Planes placed as data: an offset per object, explicit colours and alphas per plane, exactly as
// the geometric reference reads them.
TEST(Scene, PlanesArePlaceableAsData) {
  SceneDesc s = parse_scene("s.json", R"({
  "materials": { "glass": { "colour": [1, 0, 0], "alpha": 0.5 } },
  "objects": [ { "generator": "planes", "material": "glass",
                 "params": { "count": 2, "depth": 1, "offset": [0.5, -1, -2],
                             "colours": [[0, 0.25, 1], [1, 1, 0]], "alphas": [0.0001, 1] } } ],
  "views": { "fwd": { "eye": [0, 0, 3] } }
})");
  Mesh m = build_mesh(s, s.view("fwd"), Detail::Full);
  ASSERT_EQ(m.vertices.size(), 8u);
  EXPECT_FLOAT_EQ(m.vertices[0].position.z, -1.5f);
  EXPECT_FLOAT_EQ(m.vertices[4].position.z, -2.5f);
  EXPECT_FLOAT_EQ(m.vertices[0].position.x, 0.5f - 2.0f);
  EXPECT_FLOAT_EQ(m.vertices[0].colour.g, 0.25f);
  EXPECT_FLOAT_EQ(m.vertices[0].colour.a, 0.0001f);  // float vertex colours: no RGBA8 rounding here
  auto planes = analytic_planes(s, Detail::Full);
  ASSERT_TRUE(planes.has_value());
  ASSERT_EQ(planes->size(), 2u);
  EXPECT_DOUBLE_EQ((*planes)[1].centre.z, -2.5);
  EXPECT_FLOAT_EQ((*planes)[1].colour.a, 1.0f);
  EXPECT_FALSE(analytic_planes(load_scene("smoke"), Detail::Small).has_value());
}

TEST(Scene, PlaneListsMustMatchTheCount) {
  std::string msg = error_of(R"({
  "materials": { "glass": { "colour": [1, 0, 0], "alpha": 0.5 } },
  "objects": [ { "generator": "planes", "material": "glass",
                 "params": { "count": 3,
                             "alphas": [0.5, 0.5] } } ],
  "views": { "fwd": { "eye": [0, 0, 3] } }
})");
  EXPECT_EQ(msg.rfind("s.json:5:", 0), 0u) << msg;
  EXPECT_NE(msg.find("expected 3 entries"), std::string::npos) << msg;
  msg = error_of(R"({
  "materials": { "glass": { "colour": [1, 0, 0], "alpha": 0.5 } },
  "objects": [ { "generator": "planes", "material": "glass",
                 "params": { "count": 1, "colours": [[2, 0, 0]] } } ],
  "views": { "fwd": { "eye": [0, 0, 3] } }
})");
  EXPECT_EQ(msg.rfind("s.json:4:", 0), 0u) << msg;
  EXPECT_NE(msg.find("/objects/0/params/colours/0/0"), std::string::npos) << msg;
}

TEST(Scene, ShippedPrecisionScenesAreAnalytic) {
  for (const char* name : {"precision-ulp-1", "precision-ulp-3", "precision-ulp-10", "precision-ties-ab",
                           "precision-ties-ba", "precision-faint-1000", "precision-faint-5000", "precision-alpha-0-1",
                           "precision-near-far", "precision-opaque-between", "planes", "planes-deep"})
    EXPECT_TRUE(analytic_planes(load_scene(name), Detail::Small).has_value()) << name;
}

}  // namespace
}  // namespace oitbench::oit
