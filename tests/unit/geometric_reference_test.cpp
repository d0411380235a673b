// The geometric reference of analytic scenes (micro/oit/reference/geometric_reference.hpp) and the fragment
// formats' CPU side: binary16 rounding, each format's quantisation, the tie rule, layers and edges.
#include "oit/reference/geometric_reference.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "oit/capture/packed_fragment.hpp"

namespace oitbench::oit {
namespace {

SceneDesc scene_of(const std::string& objects) {
  return parse_scene("s.json", R"({
  "background": [1, 1, 1],
  "materials": { "glass": { "colour": [0.5, 0.5, 0.5], "alpha": 0.5 } },
  "objects": [ )" + objects + R"( ],
  "views": { "fwd": { "eye": [0, 0, 3], "order": "front-to-back" } }
})");
}

TEST(GeometricReference, HalfRoundsToNearestEven) {
  EXPECT_EQ(float_to_half(0.5f), 0x3800);
  EXPECT_EQ(float_to_half(65504.0f), 0x7bff);
  EXPECT_EQ(float_to_half(1e6f), 0x7c00);                   // past the largest half: infinity
  EXPECT_EQ(float_to_half(1.0f + 1.0f / 2048), 0x3c00);     // a tie: to the even 1.0
  EXPECT_EQ(float_to_half(1.0f + 3.0f / 2048), 0x3c02);     // a tie: to the even 1 + 2^-9
  EXPECT_EQ(float_to_half(std::ldexp(1.0f, -24)), 0x0001);  // the smallest subnormal
  EXPECT_FLOAT_EQ(half_to_float(float_to_half(1e-4f)), 1.0001659e-4f);
  for (uint16_t h : {0x0001, 0x03ff, 0x0400, 0x3555, 0x3c00, 0x7bff})
    EXPECT_EQ(float_to_half(half_to_float(h)), h) << h;
}

TEST(GeometricReference, EachFormatQuantisesAsItStores) {
  glm::vec4 faint(0.3f, 0.6f, 0.9f, 1e-3f);
  EXPECT_EQ(quantise_colour(faint, FragColour::RGBA8).a, 0.0);  // below 1/510: RGBA8 cannot hold it
  EXPECT_NEAR(quantise_colour(faint, FragColour::RGBA8).r, 77.0 / 255.0, 1e-12);
  EXPECT_NEAR(quantise_colour(faint, FragColour::RGBA16F).a, 1e-3, 1e-6);
  EXPECT_EQ(quantise_colour(faint, FragColour::RGBA32F).a, static_cast<double>(1e-3f));
}

TEST(GeometricReference, CompositesThePlanesInTheirTrueOrder) {
  // Two full-view planes (red nearer, alpha 0.5; blue behind, 0.25) over white.
  SceneDesc s = scene_of(R"({ "generator": "planes", "material": "glass",
      "params": { "count": 2, "depth": 1, "colours": [[1, 0, 0], [0, 0, 1]], "alphas": [0.5, 0.25] } })");
  auto ref = geometric_reference(s, s.view("fwd"), Detail::Full, {0.1f, 10.0f}, 8, 8, FragColour::RGBA32F);
  ASSERT_TRUE(ref.has_value());
  EXPECT_EQ(ref->ambiguous_pixels, 0u);
  EXPECT_EQ(ref->coplanar_pixels, 0u);
  // over: 0.5 red + 0.5 * (0.25 blue + 0.75 white)
  const double r = 0.5 + 0.5 * 0.75, g = 0.5 * 0.75, b = 0.5 * (0.25 + 0.75);  // (0.875, 0.375, 0.5)
  for (size_t p = 0; p < 64; ++p) {
    EXPECT_EQ(ref->layers[p], 2u);
    EXPECT_NEAR(ref->exact[p * 3], r, 1e-12);
    EXPECT_NEAR(ref->exact[p * 3 + 1], g, 1e-12);
    EXPECT_NEAR(ref->exact[p * 3 + 2], b, 1e-12);
  }
  // The far plane beyond the far plane of the projection is clipped away.
  auto clipped = geometric_reference(s, s.view("fwd"), Detail::Full, {0.1f, 3.2f}, 8, 8, FragColour::RGBA32F);
  EXPECT_EQ(clipped->layers[0], 1u);
  // A check against an image: a perfect one has no bad pixels; one that swapped the two has them all.
  std::vector<float> good(64 * 4, 1.0f), swapped(64 * 4, 1.0f);
  const glm::vec3 blue_over_red(0.75f, 0.375f, 0.625f);  // 0.25 blue + 0.75 (0.5 red + 0.5 white)
  for (size_t p = 0; p < 64; ++p)
    for (int k = 0; k < 3; ++k) {
      good[p * 4 + k] = static_cast<float>(ref->exact[p * 3 + k]);
      swapped[p * 4 + k] = blue_over_red[k];
    }
  std::vector<unsigned> two(64, 2);
  EXPECT_EQ(check_against_geometry(*ref, good, two, glm::vec3(1), 1e-4).bad_pixels, 0u);
  EXPECT_EQ(check_against_geometry(*ref, swapped, two, glm::vec3(1), 1e-4).bad_pixels, 64u);
  std::vector<unsigned> one(64, 1);
  auto lost = check_against_geometry(*ref, good, one, glm::vec3(1), 1e-4);
  EXPECT_EQ(lost.layer_mismatches, 64u);
  EXPECT_NE(lost.first_layer_mismatch.find("holds 1 fragment(s), the geometry 2"), std::string::npos);
}

TEST(GeometricReference, CoplanarPlanesFollowTheTieRuleInEitherOrder) {
  auto composite = [](const std::string& colours) {
    SceneDesc s = scene_of(R"({ "generator": "planes", "material": "glass",
        "params": { "count": 2, "depth": 0, "colours": )" +
                           colours + R"( } })");
    auto ref = geometric_reference(s, s.view("fwd"), Detail::Full, {0.1f, 10.0f}, 4, 4, FragColour::RGBA8);
    EXPECT_EQ(ref->coplanar_pixels, 16u);
    return ref->quantised;
  };
  EXPECT_EQ(composite("[[1, 0, 0], [0, 0, 1]]"), composite("[[0, 0, 1], [1, 0, 0]]"));
}

TEST(GeometricReference, EdgesThroughPixelCentresAreAmbiguous) {
  // A plane at z = 0 seen from z = 3 whose edge x = 0 passes through no pixel centre at an even
  // width (the centres lie half a pixel off the axis); at an odd width the centre column lies on it.
  SceneDesc s = scene_of(R"({ "generator": "planes", "material": "glass",
      "params": { "count": 1, "half_size": 0.5, "offset": [0.5, 0, 0] } })");
  auto even = geometric_reference(s, s.view("fwd"), Detail::Full, {0.1f, 10.0f}, 8, 8, FragColour::RGBA8);
  auto odd = geometric_reference(s, s.view("fwd"), Detail::Full, {0.1f, 10.0f}, 9, 9, FragColour::RGBA8);
  EXPECT_EQ(even->ambiguous_pixels, 0u);
  EXPECT_GE(odd->ambiguous_pixels, 1u);
  EXPECT_FALSE(geometric_reference(load_scene("smoke"), load_scene("smoke").view("fwd"), Detail::Small, {0.1f, 10.0f},
                                   4, 4, FragColour::RGBA8)
                   .has_value());
}

}  // namespace
}  // namespace oitbench::oit
