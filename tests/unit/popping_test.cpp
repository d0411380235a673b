// The popping metric and its camera path (micro/oit/splats/popping.hpp) on made-up frames: a technique
// that changes as the reference does pops 0, one that jumps beyond it pops by the excess (its largest
// channel), one that changes less pops 0, a NaN is the largest pop, skipped pixels count in the mean but
// not in the pixels; the path orbits the target about up, centred on the view; the reference marks the
// pixels whose order is a float tie that matters (SplatImage::tied), which an exact technique is not held to.
#include "oit/splats/popping.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "oit/splats/splat_reference.hpp"

namespace oitbench::oit {
namespace {

std::vector<float> frame(float r, float g, float b, int pixels = 4) {
  std::vector<float> f;
  for (int i = 0; i < pixels; ++i) f.insert(f.end(), {r, g, b});
  return f;
}

TEST(Popping, AChangeTheReferenceMakesTooIsNoPop) {
  PoppingMeter m(2, 2);
  m.add(frame(0.2f, 0.3f, 0.4f), frame(0.25f, 0.3f, 0.4f));
  m.add(frame(0.5f, 0.3f, 0.1f), frame(0.55f, 0.3f, 0.1f));  // same change, another offset (a biased technique)
  const Popping p = m.result();
  EXPECT_NEAR(p.mean, 0.0, 1e-7);
  EXPECT_NEAR(p.peak, 0.0, 1e-7);
  EXPECT_EQ(p.pixels, 0u);
}

TEST(Popping, AJumpBeyondTheReferencePopsByTheExcessOfItsLargestChannel) {
  PoppingMeter m(2, 2);
  const auto ref = frame(0.5f, 0.5f, 0.5f);
  auto a = frame(0.5f, 0.5f, 0.5f), b = a;
  b[3 * 3 + 0] = 0.6f;   // pixel (1,1): red +0.1
  b[3 * 3 + 2] = 0.45f;  // blue -0.05: the larger channel counts
  m.add(a, ref);
  m.add(b, ref);
  m.add(b, ref);  // a third frame with no change: two pairs in the mean
  const Popping p = m.result();
  EXPECT_NEAR(p.peak, 0.1, 1e-6);
  EXPECT_NEAR(p.mean, 0.1 / 8, 1e-6);
  EXPECT_EQ(p.pixels, 1u);
  EXPECT_NE(p.first.find("pixel (1,1) frames 0-1"), std::string::npos) << p.first;
}

TEST(Popping, ChangingLessThanTheReferenceIsNoPopAndSkippedPixelsAreNotCounted) {
  PoppingMeter m(2, 2);
  m.add(frame(0.5f, 0.5f, 0.5f), frame(0.2f, 0.2f, 0.2f));
  m.add(frame(0.55f, 0.5f, 0.5f), frame(0.8f, 0.8f, 0.8f));  // smoother than the truth
  EXPECT_EQ(m.result().peak, 0.0);
  PoppingMeter s(2, 2);
  s.add(frame(0.5f, 0.5f, 0.5f), frame(0.5f, 0.5f, 0.5f));
  s.add(frame(0.9f, 0.5f, 0.5f), frame(0.5f, 0.5f, 0.5f), {1, 1, 1, 0});
  EXPECT_EQ(s.result().pixels, 1u);  // only pixel 3 is held
  EXPECT_NEAR(s.result().mean, 0.4, 1e-6);
}

TEST(Popping, ANanIsTheLargestPop) {
  PoppingMeter m(2, 2);
  m.add(frame(0.5f, 0.5f, 0.5f), frame(0.5f, 0.5f, 0.5f));
  auto b = frame(0.5f, 0.5f, 0.5f);
  b[1] = std::numeric_limits<float>::quiet_NaN();
  m.add(b, frame(0.5f, 0.5f, 0.5f));
  EXPECT_EQ(m.result().peak, 1.0);
  EXPECT_EQ(m.result().pixels, 1u);
}

TEST(Popping, AFrameOfTheWrongSizeIsAnError) {
  PoppingMeter m(2, 2);
  EXPECT_THROW(m.add(frame(0, 0, 0, 3), frame(0, 0, 0)), std::invalid_argument);
}

TEST(Popping, ThePathOrbitsTheTargetCentredOnTheView) {
  View v;
  v.eye = {1, 2, 5};
  v.target = {1, 0, 1};
  v.up = {0, 1, 0};
  const CameraPath path{8, 2.0};
  const View mid = path_view(v, path, 4);
  EXPECT_NEAR(glm::distance(mid.eye, v.eye), 0.0f, 1e-6f);
  for (int k = 0; k <= 8; ++k) {
    const View f = path_view(v, path, k);
    EXPECT_NEAR(glm::distance(f.eye, v.target), glm::distance(v.eye, v.target), 1e-5f) << k;
    EXPECT_NEAR(f.eye.y, v.eye.y, 1e-6f) << k << ": about the up axis";
    EXPECT_EQ(f.target, v.target);
  }
  // frame 0 is 8 degrees to one side: +x is to the right of the view, so a negative angle moves the eye left
  const glm::vec3 a = path_view(v, path, 0).eye - v.target, b = v.eye - v.target;
  const double angle = std::acos(glm::dot(glm::normalize(glm::vec2(a.x, a.z)), glm::normalize(glm::vec2(b.x, b.z))));
  EXPECT_NEAR(angle, glm::radians(8.0), 1e-5);
  EXPECT_LT(a.x, 0.0f);
}

// Two splats at one place (equal keys) tie where swapping them matters, not where one is 0.01 behind,
// nor where both are too faint for the swap to move the pixel by 1/255.
TEST(Popping, TheReferenceMarksTheFloatTiesThatMatter) {
  View v;
  v.eye = {0, 0, 4};
  const SplatCamera cam = splat_camera(v, 32, 32, 0.1);
  Splat a;
  a.scale = glm::vec3(0.1f);
  a.opacity = 0.8f;
  a.colour = {1, 0, 0};
  Splat b = a;
  b.colour = {0, 0, 1};
  auto tied_pixels = [&](float dz, float opacity) {
    Splat x = a, y = b;
    y.position.z -= dz;
    x.opacity = y.opacity = opacity;
    const SplatImage img = splat_reference({x, y}, cam, {});
    return std::count(img.tied.begin(), img.tied.end(), 1);
  };
  EXPECT_GT(tied_pixels(0.0f, 0.8f), 8);
  EXPECT_EQ(tied_pixels(0.01f, 0.8f), 0);
  EXPECT_EQ(tied_pixels(0.0f, 0.05f), 0);  // 0.05 x 0.05 x 1 < 1/255
}

// The slack splat_check allows at a tied pixel is what the GPU's other order of the tie gives: the same two
// splats submitted the other way round (equal keys: the submission order decides) move each tied pixel by at
// most its tie_slack, and by more than a check's tolerance somewhere; untied pixels have no slack.
TEST(Popping, ATiesSlackBoundsTheOtherOrder) {
  View v;
  v.eye = {0, 0, 4};
  const SplatCamera cam = splat_camera(v, 32, 32, 0.1);
  Splat a;
  a.scale = glm::vec3(0.1f);
  a.opacity = 0.8f;
  a.colour = {1, 0, 0};
  Splat b = a;
  b.colour = {0, 0, 1};
  const SplatImage one = splat_reference({a, b}, cam, {});
  const SplatImage other = splat_reference({b, a}, cam, {});
  double largest = 0;
  for (size_t p = 0; p < one.rgba.size(); ++p) {
    const glm::dvec3 e = glm::abs(glm::dvec3(one.rgba[p]) - glm::dvec3(other.rgba[p]));
    const double d = std::max({e.r, e.g, e.b});
    largest = std::max(largest, d);
    EXPECT_LE(d, one.tie_slack[p] + kSplatTieEffect) << "pixel " << p;  // a smaller swap is not a tie
    if (!one.tied[p]) {
      EXPECT_EQ(one.tie_slack[p], 0.0f);
    }
  }
  EXPECT_GT(largest, 0.1);
}

}  // namespace
}  // namespace oitbench::oit
