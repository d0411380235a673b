// The viewer's parts that need no window: the key script, saving a view into a scene file as text,
// the fly camera, the rolling medians and the keys' effect on the oit parameters.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/params.hpp"
#include "experiments/experiments.hpp"
#include "support/test_support.hpp"
#include "viewer/fly_camera.hpp"
#include "viewer/key_script.hpp"
#include "viewer/oit_settings.hpp"
#include "viewer/rolling_medians.hpp"
#include "viewer/scene_views.hpp"

namespace oitbench::viewer {
namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(KeyScript, ParsesFramesKeysShiftAndEscapeInFrameOrder) {
  auto keys = parse_key_script("6:V, 2:t,4:shift+M,2:Z,9:Esc");
  ASSERT_EQ(keys.size(), 5u);
  EXPECT_EQ(keys[0].frame, 2);
  EXPECT_EQ(keys[0].press, (KeyPress{'T', false}));
  EXPECT_EQ(keys[1].press, (KeyPress{'Z', false}));  // same frame: script order kept
  EXPECT_EQ(keys[2].press, (KeyPress{'M', true}));
  EXPECT_EQ(keys[3].press, (KeyPress{'V', false}));
  EXPECT_EQ(keys[4].press, (KeyPress{kEscape, false}));
  EXPECT_EQ(key_name(keys[2].press), "shift+M");
  EXPECT_TRUE(parse_key_script("").empty());
}

TEST(KeyScript, BadEntriesAreUsageErrorsShowingTheSyntax) {
  for (const char* bad : {"T", "2:", "x:T", "-1:T", "2:TT", "2:T,,3:Z", "2:shift+"}) {
    try {
      parse_key_script(bad);
      ADD_FAILURE() << bad << " parsed";
    } catch (const UsageError& e) {
      EXPECT_NE(std::string(e.what()).find("FRAME:KEY"), std::string::npos) << e.what();
    }
  }
}

oit::View a_view(const std::string& name) {
  oit::View v;
  v.name = name;
  v.eye = {1.0f / 3.0f, -2.0f, 4.5f};
  v.target = {0, 0, 0};
  v.fov_deg = 50;
  v.order = oit::SubmitOrder::BackToFront;
  return v;
}

TEST(SceneViews, InsertedAfterTheLastViewIndentedLikeTheOthersAndNothingElseChanges) {
  std::string text = slurp(oit::default_scene_dir() + "/planes.json");
  std::string out = insert_view("planes.json", text, a_view("mine"));
  // Everything before and after the inserted text is the file as it was.
  size_t at = text.find("\"order\": \"as-generated\" }\n  }");
  ASSERT_NE(at, std::string::npos);
  at = text.find('}', at) + 1;  // the end of the last view
  std::string inserted =
      ",\n    \"mine\": { \"eye\": [0.3333, -2, 4.5], \"target\": [0, 0, 0], \"up\": [0, 1, 0], "
      "\"fov\": 50, \"order\": \"back-to-front\" }";
  EXPECT_EQ(out, text.substr(0, at) + inserted + text.substr(at));
  oit::SceneDesc s = oit::parse_scene("planes.json", out);
  EXPECT_NEAR(s.view("mine").eye.x, 0.3333f, 1e-6f);
  EXPECT_EQ(s.view("mine").order, oit::SubmitOrder::BackToFront);
  EXPECT_EQ(view_names_in_file_order("planes.json", out), (std::vector<std::string>{"fwd", "rev", "mine"}));
}

TEST(SceneViews, CompactAndEmptyViewObjectsAndEscapedNames) {
  auto views_of = [](const std::string& text) { return nlohmann::ordered_json::parse(text)["views"]; };
  std::string compact = R"({"views": {"b": {"eye": [0, 0, 3]}, "a": {"eye": [0, 0, -3]}}, "name": "x"})";
  std::string out = insert_view("c.json", compact, a_view("c"));
  EXPECT_TRUE(out.ends_with("\"back-to-front\" }}, \"name\": \"x\"}")) << out;
  auto v = views_of(out);
  ASSERT_EQ(v.size(), 3u);
  EXPECT_EQ(v.begin().key(), "b");
  EXPECT_EQ(v["c"]["eye"][2], 4.5);
  EXPECT_EQ(view_names_in_file_order("c.json", compact), (std::vector<std::string>{"b", "a"}));

  EXPECT_EQ(views_of(insert_view("e.json", R"({"views": {}})", a_view("q\"uote"))).begin().key(), "q\"uote");
  std::string multi = "{\n  \"views\": {\n  }\n}\n";
  out = insert_view("m.json", multi, a_view("n"));
  EXPECT_EQ(out.find("\n    \"n\": {"), multi.find("\n  }"));
  EXPECT_EQ(views_of(out).size(), 1u);

  EXPECT_THROW(insert_view("n.json", R"({"materials": {}})", a_view("x")), oit::SceneError);
}

TEST(SceneViews, NamesNeverClash) {
  EXPECT_EQ(unique_view_name({}, ""), "view-1");
  EXPECT_EQ(unique_view_name({"view-1", "fwd"}, ""), "view-2");
  EXPECT_EQ(unique_view_name({"fwd"}, "close"), "close");
  EXPECT_EQ(unique_view_name({"close", "close-2"}, "close"), "close-3");
}

TEST(SceneViews, SavedTwiceIntoACopyOfAShippedSceneWhichStillLoads) {
  auto dir = test::temp_dir("viewer-save");
  std::string path = (dir / "planes.json").string();
  std::string original = slurp(oit::default_scene_dir() + "/planes.json");
  std::ofstream(path) << original;
  oit::View v = a_view("");
  EXPECT_EQ(save_view_to_scene_file(path, v, ""), "view-1");
  v.eye = {0, 1, 2};
  EXPECT_EQ(save_view_to_scene_file(path, v, ""), "view-2");
  EXPECT_EQ(save_view_to_scene_file(path, v, "fwd"), "fwd-2");
  oit::SceneDesc s = oit::load_scene(path);
  EXPECT_NEAR(s.view("view-1").eye.z, 4.5f, 1e-6f);
  EXPECT_NEAR(s.view("view-2").eye.y, 1.0f, 1e-6f);
  EXPECT_NEAR(s.view("fwd").eye.z, 3.0f, 1e-6f);  // untouched
  EXPECT_EQ(s.views.size(), 5u);
  std::string now = slurp(path);
  size_t last_view_end = original.rfind("\n  }");
  EXPECT_EQ(now.substr(0, last_view_end), original.substr(0, last_view_end));
  EXPECT_EQ(now.substr(now.size() - (original.size() - last_view_end)), original.substr(last_view_end));
  EXPECT_FALSE(std::filesystem::exists(path + ".oitbench-tmp"));
}

TEST(SceneViews, ABrokenSceneFileIsLeftAlone) {
  auto dir = test::temp_dir("viewer-broken");
  std::string path = (dir / "broken.json").string();
  std::ofstream(path) << "{ \"views\": { \"a\": { \"eye\": [0, 0, 3] } }";
  EXPECT_THROW(save_view_to_scene_file(path, a_view(""), ""), oit::SceneError);
  EXPECT_EQ(slurp(path), "{ \"views\": { \"a\": { \"eye\": [0, 0, 3] } }");
}

TEST(FlyCamera, StartsAtTheViewMovesAndLooksWithoutLosingUp) {
  oit::SceneDesc planes = oit::load_scene("planes");
  const oit::View& fwd = planes.view("fwd");
  oit::Mesh mesh = oit::build_mesh(planes, fwd, oit::Detail::Small);
  FlyCamera cam(fwd, mesh);
  EXPECT_EQ(cam.view().eye, fwd.eye);
  EXPECT_NEAR(glm::distance(cam.view().target, fwd.target), 0.0f, 1e-6f);
  EXPECT_NEAR(cam.speed(), 0.25f * std::sqrt(4.0f * 4.0f * 2 + 2.0f * 2.0f), 1e-4f);  // a quarter of the diagonal
  float speed = cam.speed();
  cam.move({1, 0, 0, false}, 1.0f);
  EXPECT_NEAR(cam.view().eye.z, 3.0f - speed, 1e-5f);
  cam.move({0, 1, 0, true}, 0.5f);  // shift: 4x
  EXPECT_NEAR(cam.view().eye.x, 2.0f * speed, 1e-5f);
  cam.look(0, -1e4f);  // far past straight up: stops short of it
  glm::vec3 dir = glm::normalize(cam.view().target - cam.view().eye);
  EXPECT_LT(std::abs(glm::dot(dir, glm::vec3(0, 1, 0))), 1.0f);
  EXPECT_GT(dir.y, 0.9f);
  cam.scale_speed(2);
  EXPECT_NEAR(cam.speed(), speed * 1.5625f, 1e-4f);
  glm::mat4 vp = cam.view_projection(4.0f / 3.0f);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_TRUE(std::isfinite(vp[c][r]));
}

TEST(RollingMedians, MedianOverTheLastWindowInFirstSeenOrder) {
  RollingMedians m(3);
  for (double v : {100.0, 1.0, 2.0, 3.0}) m.add("resolve", v);
  m.add("capture", 5);
  m.add("capture", 7);
  EXPECT_DOUBLE_EQ(m.median("resolve"), 2.0);  // 100 has left the window
  EXPECT_DOUBLE_EQ(m.median("capture"), 6.0);
  EXPECT_EQ(m.samples("resolve"), 3u);
  auto all = m.medians();
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].first, "resolve");
}

class OitSettingsTest : public ::testing::Test {
 protected:
  void SetUp() override { register_all_experiments(registry_); }
  Registry registry_;
};

TEST_F(OitSettingsTest, ValuesAreCheckedAgainstTheExperimentListingValidOnes) {
  try {
    OitSettings s(registry_, {{"technique", "bogus"}});
    FAIL() << "accepted";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("BMA-RBS-L"), std::string::npos) << e.what();
  }
  EXPECT_THROW(OitSettings(registry_, {{"no_such", "1"}}), UsageError);
  OitSettings s(registry_, {{"technique", "BASE-IS"}, {"detail", "small"}});
  EXPECT_EQ(s.get("detail"), "small");
  EXPECT_EQ(s.get("max_frags"), "0");  // the experiment's default
}

TEST_F(OitSettingsTest, KeysStepTechniquesToggleBmaAndScaleMaxFrags) {
  OitSettings s(registry_, {{"technique", "BASE-IS"}});
  bool changed = false;
  s.step_technique(-1, changed);
  EXPECT_TRUE(changed);
  EXPECT_EQ(s.technique(), "unsorted");  // wraps to the last approximate technique
  s.step_technique(1, changed);
  EXPECT_EQ(s.technique(), "BASE-IS");
  s.toggle_bma(changed);
  EXPECT_EQ(s.technique(), "BMA-IS");
  s.toggle_bma(changed);
  EXPECT_EQ(s.technique(), "BASE-IS");

  s.scale_max_frags(true, 32, changed);  // auto chose 32
  EXPECT_EQ(s.get("max_frags"), "64");
  s.scale_max_frags(false, 64, changed);
  s.scale_max_frags(false, 32, changed);
  EXPECT_EQ(s.get("max_frags"), "16");
  s.set("max_frags", "1");
  s.scale_max_frags(false, 1, changed);
  EXPECT_TRUE(changed);
  EXPECT_EQ(s.get("max_frags"), "0");  // below 1: auto
  s.set("max_frags", "4096");
  s.scale_max_frags(true, 4096, changed);
  EXPECT_FALSE(changed);

  s.set("technique", "CPU-NATIVE");
  std::string note = s.toggle_bma(changed);
  EXPECT_FALSE(changed);
  EXPECT_NE(note.find("no BASE/BMA twin"), std::string::npos);
  s.scale_max_frags(true, 32, changed);
  EXPECT_FALSE(changed);

  s.set("technique", "MLAB");
  s.scale_max_frags(true, 8, changed);
  EXPECT_EQ(s.get("nodes"), "16");
  s.set("nodes", "64");
  s.scale_max_frags(true, 64, changed);
  EXPECT_FALSE(changed);
  EXPECT_EQ(s.get("nodes"), "64");
}

TEST_F(OitSettingsTest, CaptureStorageKeyCyclesThroughTheExperimentsLayouts) {
  OitSettings s(registry_, {});
  EXPECT_EQ(s.get("capture"), "PPLL");
  bool changed = false;
  EXPECT_EQ(s.step_capture(changed), "capture storage PPPA");
  EXPECT_TRUE(changed);
  EXPECT_EQ(s.get("capture"), "PPPA");
  s.step_capture(changed);
  EXPECT_EQ(s.get("capture"), "PPLL");
}

}  // namespace
}  // namespace oitbench::viewer
