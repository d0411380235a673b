// Scene files: the shipped scenes load and generate what they promise; broken files give an error
// naming the file, the line and column, and what was expected.
#include <gtest/gtest.h>

#include "oit/scene.hpp"

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
  for (const char* name : {"planes", "hairball", "smoke"}) {
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
    if (order == SubmitOrder::FrontToBack) EXPECT_GT(first, last);  // the eye is at +z
    else EXPECT_LT(first, last);
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

TEST(Scene, ModelScenesLoadThroughAssimp) {
  for (const char* name : {"engine-grid", "house"}) {
    SceneDesc s = load_scene(name);
    try {
      Mesh m = build_mesh(s, s.view("fwd"), Detail::Small);
      EXPECT_GT(m.polygons(), 1000u) << name;
    } catch (const SceneError& e) {
      if (std::string(e.what()).find("not found") != std::string::npos) GTEST_SKIP() << e.what();
      throw;
    }
  }
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
