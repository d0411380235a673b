// `oitbench view` end to end. ctest runs each test under its own Xvfb (tests/CMakeLists.txt:
// xvfb-run -a), so the binary these tests start opens a real GLFW window; NoDisplay takes the
// display away again.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#include <stb_image.h>
#pragma GCC diagnostic pop

#include "oit/scene/scene.hpp"
#include "support/test_support.hpp"

namespace oitbench::test {
namespace {

bool contains(const std::string& s, const std::string& what) { return s.find(what) != std::string::npos; }

struct Image {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;  // rows from the top
  glm::ivec3 at(int x, int y) const {
    size_t i = (static_cast<size_t>(y) * width + x) * 3;
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
};

std::optional<Image> read_png(const std::filesystem::path& path) {
  int w = 0, h = 0, n = 0;
  unsigned char* data = stbi_load(path.c_str(), &w, &h, &n, 3);
  if (!data) return std::nullopt;
  Image img{w, h, std::vector<unsigned char>(data, data + static_cast<size_t>(w) * h * 3)};
  stbi_image_free(data);
  return img;
}

// The small test window: 160x120 shows only two overlay lines and the message at the top left,
// so the lower half is the image.
const std::vector<std::string> kSmallPlanes = {"view", "--scene", "planes", "--detail", "small", "--size", "160x120"};

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

TEST(Viewer, RendersFramesAndSavesTheWindowAsPng) {
  auto png = temp_dir("viewer-shot") / "out.png";
  auto r = run_oitbench(with(kSmallPlanes, {"--frames", "8", "--screenshot", png.string(), "--keys", "1:H,3:H"}), 120);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto img = read_png(png);
  ASSERT_TRUE(img) << png;
  EXPECT_EQ(img->width, 160);
  EXPECT_EQ(img->height, 120);
  // planes: every pixel sees the stacked glass; the scene's background is white.
  glm::ivec3 centre = img->at(80, 90);
  EXPECT_NE(centre, glm::ivec3(255)) << "the window shows only the background";
  EXPECT_GT(centre.x, 60);  // tinted glass, not black
  EXPECT_TRUE(contains(r.err, "BASE-IS ready")) << r.err;
}

TEST(Viewer, DepthComplexityShowsThePeakInRed) {
  auto png = temp_dir("viewer-depth") / "depth.png";
  auto r = run_oitbench(with(kSmallPlanes, {"--frames", "4", "--screenshot", png.string(), "--keys", "1:Z"}), 120);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto img = read_png(png);
  ASSERT_TRUE(img);
  // 24 planes cover the centre: the peak depth there, red on the log scale.
  EXPECT_EQ(img->at(80, 90), glm::ivec3(255, 0, 0));
  EXPECT_TRUE(contains(r.err, "depth complexity on")) << r.err;
}

TEST(Viewer, CWalksThePackedArraysCaptureAndItsDepthComplexity) {
  // C: PPLL -> PPPA; the case is rebuilt on packed arrays and Z counts them through the storage API.
  auto png = temp_dir("viewer-pppa") / "pppa.png";
  auto r = run_oitbench(with(kSmallPlanes, {"--frames", "5", "--screenshot", png.string(), "--keys", "1:C,3:Z"}), 120);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.err, "capture storage PPPA")) << r.err;
  auto img = read_png(png);
  ASSERT_TRUE(img);
  EXPECT_EQ(img->at(80, 90), glm::ivec3(255, 0, 0));  // 24 planes at the centre: the peak, red
}

// Pixels of the lower half (below the overlay) that differ from the white background.
int non_background_below_overlay(const Image& img) {
  int n = 0;
  for (int y = img.height / 2; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) n += glm::any(glm::lessThan(img.at(x, y), glm::ivec3(245)));
  return n;
}

TEST(Viewer, ShowsGeneratedAndPlySplatScenes) {
  // Issue 29: the viewer shows splat scenes, generated (with the 3DGS global sort) and read from a PLY
  // file (with an exact per-pixel resolve).
  for (const auto& [scene, technique] : {std::pair<std::string, std::string>{"splats", "GLOBAL-SORT"},
                                         std::pair<std::string, std::string>{"splats-ply", "BASE-IS"}}) {
    auto png = temp_dir("viewer-" + scene) / "shot.png";
    auto r = run_oitbench({"view", "--scene", scene, "--detail", "small", "--size", "160x120", "--technique", technique,
                           "--frames", "3", "--screenshot", png.string()},
                          180);
    ASSERT_EQ(r.exit_code, 0) << scene << ": " << r.err;
    EXPECT_TRUE(contains(r.err, technique + " ready")) << r.err;
    auto img = read_png(png);
    ASSERT_TRUE(img) << png;
    EXPECT_GT(non_background_below_overlay(*img), 40) << scene << ": the window shows only the background";
  }
}

TEST(Viewer, KeysSwitchTechniqueBmaMaxFragsAndApproximate) {
  auto png = temp_dir("viewer-keys") / "keys.png";
  // BASE-IS -B-> BMA-IS -M-> MAX_FRAGS 64 -B-> BASE-IS -shift+T-> unsorted (approximate, the last
  // technique), where Z and M have nothing to work on and say so (C switches its reference's capture).
  auto r = run_oitbench(with(kSmallPlanes, {"--frames", "10", "--screenshot", png.string(), "--keys",
                                            "1:B,2:M,3:B,4:shift+T,5:Z,6:C,7:shift+M"}),
                        240);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* said :
       {"BMA-IS ready", "MAX_FRAGS 64", "technique BASE-IS", "unsorted ready", "M: unsorted has no MAX_FRAGS"})
    EXPECT_TRUE(contains(r.err, said)) << said << " missing in:\n" << r.err;
  auto img = read_png(png);
  ASSERT_TRUE(img);
  EXPECT_NE(img->at(80, 90), glm::ivec3(255));
}

TEST(Viewer, ATechniqueThatCannotBeBuiltKeepsThePreviousOneAndExitsOne) {
  // LAAT under sync=interlock needs ARB_fragment_shader_interlock (llvmpipe has none).
  auto r = run_oitbench(
      with(kSmallPlanes, {"--technique", "WBOIT", "--set", "sync=interlock", "--frames", "4", "--keys", "1:shift+T"}),
      120);
  if (contains(r.err, "LAAT ready")) GTEST_SKIP() << "this driver has fragment shader interlock";
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(contains(r.err, "cannot build LAAT: sync=interlock needs")) << r.err;
  EXPECT_TRUE(contains(r.err, "oitbench view: WBOIT:")) << r.err;  // the summary: still WBOIT
}

// The viewer's cases are held against the memory limit like a run's: MLAB's node arrays (64 nodes at
// 128x128, 8 MiB) under --memory-limit 4M are not built (exit 1 naming them and the limit); under 1G
// the same case is built and drawn.
TEST(Viewer, ATechniqueOverTheMemoryLimitIsNotBuilt) {
  auto view = [&](const char* limit) {
    return run_oitbench({"view", "--scene", "planes", "--detail", "small", "--size", "128x128", "--technique", "MLAB",
                         "--set", "nodes=64", "--frames", "2", "--memory-limit", limit},
                        120);
  };
  auto refused = view("4M");
  EXPECT_EQ(refused.exit_code, 1) << refused.err;
  EXPECT_TRUE(contains(refused.err, "cannot build MLAB: MLAB's node arrays: needs 8.06 MiB")) << refused.err;
  EXPECT_TRUE(contains(refused.err, "limit 4.00 MiB (--memory-limit)")) << refused.err;
  auto built = view("1G");
  EXPECT_EQ(built.exit_code, 0) << built.err;
  EXPECT_TRUE(contains(built.err, "MLAB ready")) << built.err;
}

TEST(Viewer, SavesTheCameraAsANamedViewIntoTheSceneFile) {
  auto dir = temp_dir("viewer-save");
  std::string scene = (dir / "planes.json").string();
  {
    std::ifstream in(oit::default_scene_dir() + "/planes.json");
    std::ofstream out(scene);
    out << in.rdbuf();
  }
  // W twice: 0.2 s at the start speed (a quarter of the 6-unit diagonal per second) towards the target.
  auto r = run_oitbench({"view", "--scene", scene, "--detail", "small", "--size", "160x120", "--frames", "5", "--keys",
                         "1:W,2:W,3:V,4:V", "--save-view", "closer"},
                        120);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.err, "saved view \"closer\"")) << r.err;
  oit::SceneDesc s = oit::load_scene(scene);
  const oit::View& v = s.view("closer");
  EXPECT_NEAR(v.eye.x, 0.0f, 1e-4f);
  EXPECT_NEAR(v.eye.y, 0.0f, 1e-4f);
  EXPECT_NEAR(v.eye.z, 3.0f - 0.2f * 1.5f, 1e-3f);
  EXPECT_NEAR(v.target.z, v.eye.z - 3.0f, 1e-3f);  // the start view's focus distance
  EXPECT_EQ(s.view("closer-2").eye, v.eye);        // the second V: a new name, never an overwrite
  EXPECT_EQ(s.view("fwd").eye, glm::vec3(0, 0, 3));
}

TEST(Viewer, BadTechniqueListsTheValidOnes) {
  auto r = run_oitbench(with(kSmallPlanes, {"--technique", "bogus", "--frames", "1"}), 60);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "BMA-RBS-L")) << r.err;
  EXPECT_TRUE(contains(r.err, "unsorted")) << r.err;
  r = run_oitbench(with(kSmallPlanes, {"--view", "sideways", "--frames", "1"}), 60);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "views: fwd, rev")) << r.err;
  r = run_oitbench(with(kSmallPlanes, {"--frames", "3", "--keys", "5:T"}), 60);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "never reached")) << r.err;
}

TEST(Viewer, NoDisplayIsAClearError) {
  std::map<std::string, std::string> saved;
  for (const char* name : {"DISPLAY", "WAYLAND_DISPLAY"})
    if (const char* v = std::getenv(name)) saved[name] = v;
  for (const auto& [name, v] : saved) unsetenv(name.c_str());
  auto r = run_oitbench(with(kSmallPlanes, {"--frames", "1"}), 60);
  for (const auto& [name, v] : saved) setenv(name.c_str(), v.c_str(), 1);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_TRUE(contains(r.err, "DISPLAY")) << r.err;
  EXPECT_TRUE(contains(r.err, "xvfb-run")) << r.err;
}

}  // namespace
}  // namespace oitbench::test
