// WINDOW-SORT's CPU model (micro/oit/approx/window_model.cpp): fragments replayed in the global order
// through a sorted window that blends its nearest as it overflows. A window at least as long as the
// farthest displacement gives the exact front-to-back composite; a shorter one blends a fragment too early;
// the global order comes from the first capture, the fragments' own keys from the second.
#include <gtest/gtest.h>

#include <bit>

#include "oit/approx/approx_model.hpp"

namespace oitbench::oit {

namespace {

// One pixel whose fragments arrived in this order: (order key, own key, RGBA8 colour) each.
struct Arrival {
  float order_key, own_key;
  glm::vec4 colour;
};
HostLists one_pixel(const std::vector<Arrival>& arrivals, bool own) {
  HostLists l;
  l.width = l.height = 1;
  l.heads = {kListEnd};
  for (const Arrival& a : arrivals) {  // the linked list prepends: its head is the last arrival
    l.nodes.push_back({pack_rgba8(a.colour), std::bit_cast<unsigned>(own ? a.own_key : a.order_key)});
    l.next.push_back(l.heads[0]);
    l.heads[0] = static_cast<unsigned>(l.nodes.size() - 1);
  }
  return l;
}
glm::vec3 over(const std::vector<glm::vec4>& near_to_far, glm::vec3 bg) {
  glm::vec3 c(0.0f);
  float t = 1.0f;
  for (const glm::vec4& k : near_to_far) {
    c += t * k.a * glm::vec3(k);
    t *= 1.0f - k.a;
  }
  return c + t * bg;
}
glm::vec3 model(const std::vector<Arrival>& a, int window) {
  ApproxModel m = window_sort_model(one_pixel(a, false), one_pixel(a, true), Backdrop(glm::vec3(1.0f)), window);
  EXPECT_TRUE(m.error.empty()) << m.error;
  return {m.rgb[0], m.rgb[1], m.rgb[2]};
}
void expect_near(glm::vec3 a, glm::vec3 b, const char* what) {
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k], b[k], 1e-6) << what << " channel " << k;
}

const glm::vec4 kRed(1, 0, 0, 0.6f), kGreen(0, 1, 0, 0.6f), kBlue(0, 0, 1, 0.6f);

}  // namespace

// Arrival (global) order: red, green, blue by their centres; by their own keys blue is nearest, then red.
const std::vector<Arrival> kSwap = {{1.0f, 0.5f, kRed}, {2.0f, 0.9f, kGreen}, {3.0f, 0.1f, kBlue}};

TEST(WindowModel, AWindowAsLongAsTheDisplacementIsExact) {
  const glm::vec3 exact = over({kBlue, kRed, kGreen}, glm::vec3(1.0f));
  expect_near(model(kSwap, 3), exact, "window 3");
  expect_near(model(kSwap, 2), exact, "window 2: blue is two places early");
}

TEST(WindowModel, AShortWindowBlendsTooEarly) {
  // window 1: red waits; green arrives, red (nearer) leaves; blue arrives, blue (nearer than green) leaves;
  // green is flushed: red, blue, green.
  expect_near(model(kSwap, 1), over({kRed, kBlue, kGreen}, glm::vec3(1.0f)), "window 1");
  const glm::vec3 exact = over({kBlue, kRed, kGreen}, glm::vec3(1.0f));
  EXPECT_GT(std::abs(model(kSwap, 1).x - exact.x), 0.05f);
}

TEST(WindowModel, TheGlobalOrderComesFromTheOrderKeysStably) {
  // Arrival order is not the global order: the order keys put blue (arrived last) first; equal order keys
  // keep their arrival order. With a window of 1 the result shows the replayed order.
  const std::vector<Arrival> a = {{2.0f, 0.5f, kRed}, {2.0f, 0.4f, kGreen}, {1.0f, 0.9f, kBlue}};
  // global order: blue, red, green; window 1: blue waits; red arrives, red (0.5 < 0.9) leaves; green
  // arrives, green (0.4) leaves; blue is flushed: red, green, blue.
  expect_near(model(a, 1), over({kRed, kGreen, kBlue}, glm::vec3(1.0f)), "replayed order");
}

TEST(WindowModel, CapturesThatDisagreeAreAnError) {
  HostLists order = one_pixel(kSwap, false), keys = one_pixel({kSwap[0]}, true);
  ApproxModel m = window_sort_model(order, keys, Backdrop(glm::vec3(1.0f)), 4);
  EXPECT_NE(m.error.find("3 fragments captured with the centre key, 1 with the case's key"), std::string::npos)
      << m.error;
}

}  // namespace oitbench::oit
