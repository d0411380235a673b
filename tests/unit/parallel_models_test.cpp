// The CPU models and the geometric reference spread their pixels' rows over the cores
// (core/parallel_rows.hpp): the same numbers with one thread and with several, bit for bit, on random
// fragments; a model's first error is the first pixel in pixel order whichever thread met it; and the
// shared geometric reference's key changes with everything the reference reads.
#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <random>

#include "core/parallel_rows.hpp"
#include "core/shared_cache.hpp"
#include "oit/approx/approx_model.hpp"
#include "oit/moments/moment_model.hpp"
#include "oit/reference/geometric_reference.hpp"
#include "oit/slab/slab.hpp"

namespace oitbench::oit {
namespace {

constexpr int kWidth = 13, kHeight = 7;  // more rows than threads, rows not a multiple of them

// Random lists: 0-9 fragments a pixel, random colours and depths, in random arrival order.
HostLists random_lists(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  HostLists l;
  l.width = kWidth;
  l.height = kHeight;
  l.heads.assign(static_cast<size_t>(kWidth) * kHeight, kListEnd);
  for (size_t p = 0; p < l.heads.size(); ++p) {
    const int n = static_cast<int>(rng() % 10);
    for (int i = 0; i < n; ++i) {
      glm::vec4 c(unit(rng), unit(rng), unit(rng), 0.05f + 0.9f * unit(rng));
      l.nodes.push_back({pack_rgba8(c), std::bit_cast<unsigned>(0.1f + 0.8f * unit(rng))});
      l.next.push_back(l.heads[p]);
      l.heads[p] = static_cast<unsigned>(l.nodes.size() - 1);
    }
  }
  return l;
}

std::vector<CoverageFragment> random_coverage(unsigned seed, int samples) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<CoverageFragment> out;
  const unsigned all = samples >= 32 ? 0xFFFFFFFFu : (1u << samples) - 1u;
  for (int i = 0; i < 400; ++i) {
    glm::vec4 c(unit(rng), unit(rng), unit(rng), 0.05f + 0.9f * unit(rng));
    out.push_back({static_cast<unsigned>(rng() % (kWidth * kHeight)), static_cast<unsigned>(rng() % 50),
                   static_cast<unsigned>(rng()) & all, pack_rgba8(c), unit(rng)});
  }
  return out;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

}  // namespace

TEST(ParallelRows, EveryPixelOnceOnAThreadBelowTheCount) {
  for (unsigned threads : {1u, 2u, 3u, 64u}) {
    std::vector<int> seen(kWidth * kHeight, 0);
    const unsigned used = parallel_row_threads(kHeight, threads);
    EXPECT_LE(used, static_cast<unsigned>(kHeight));
    std::vector<unsigned> thread_of(seen.size());
    parallel_rows(seen.size(), kWidth, threads, [&](unsigned t, size_t p) {
      ++seen[p];
      thread_of[p] = t;
    });
    for (size_t p = 0; p < seen.size(); ++p) {
      EXPECT_EQ(seen[p], 1) << "pixel " << p << ", " << threads << " threads";
      EXPECT_LT(thread_of[p], used);
    }
  }
}

TEST(ParallelModels, EveryApproximateModelIsTheSameOnAnyNumberOfThreads) {
  const HostLists l = random_lists(1);
  Backdrop bg(glm::vec3(0.2f, 0.4f, 0.6f));
  using T = ApproxTechnique;
  for (T tech : {T::Mlab, T::Umlab, T::Ht, T::At, T::Hat, T::Uat, T::Uhat, T::Laat, T::Wboit, T::Unsorted,
                 T::GlobalSort, T::FirstK}) {
    ApproxSettings s;
    s.technique = tech;
    s.nodes = 4;
    s.threads = 1;
    const ApproxModel one = approx_model(l, bg, s);
    for (unsigned threads : {2u, 3u, 5u}) {
      s.threads = threads;
      const ApproxModel many = approx_model(l, bg, s);
      EXPECT_TRUE(same_bits(one.rgb, many.rgb)) << "technique " << static_cast<int>(tech) << ", " << threads;
      EXPECT_EQ(one.error, many.error);
    }
  }
}

TEST(ParallelModels, TheWindowModelNamesTheSameFirstBadPixelOnAnyNumberOfThreads) {
  const HostLists order = random_lists(2);
  HostLists keys = order;  // the same fragments, their own keys nearer
  for (auto& node : keys.nodes) node.y = std::bit_cast<unsigned>(std::bit_cast<float>(node.y) * 0.5f);
  const ApproxModel one = window_sort_model(order, keys, Backdrop(glm::vec3(1.0f)), 3, 1);
  ASSERT_TRUE(one.error.empty()) << one.error;
  EXPECT_TRUE(same_bits(one.rgb, window_sort_model(order, keys, Backdrop(glm::vec3(1.0f)), 3, 3).rgb));
  // Two pixels on rows that different threads take (4 and 1) lose their lists in the second capture: the
  // first in pixel order is named, whichever thread met its pixel first.
  auto first_with_fragments = [&](int y) {
    for (int x = 0; x < kWidth; ++x)
      if (order.heads[static_cast<size_t>(y) * kWidth + x] != kListEnd) return static_cast<size_t>(y) * kWidth + x;
    ADD_FAILURE() << "row " << y << " has no fragments";
    return size_t{0};
  };
  const size_t low = first_with_fragments(1), high = first_with_fragments(4);
  HostLists broken = keys;
  broken.heads[high] = kListEnd;
  broken.heads[low] = kListEnd;
  const std::string expected = "pixel " + std::to_string(low) + ":";
  for (unsigned threads : {1u, 2u, 4u}) {
    const ApproxModel m = window_sort_model(order, broken, Backdrop(glm::vec3(1.0f)), 3, threads);
    EXPECT_EQ(m.error.rfind(expected, 0), 0u) << m.error << " (" << threads << " threads)";
  }
}

TEST(ParallelModels, StochasticAndSlabModelsAreTheSameOnAnyNumberOfThreads) {
  const HostLists centre = random_lists(3);
  Backdrop bg(glm::vec3(0.9f, 0.8f, 0.7f));
  const auto coverage = random_coverage(4, 8);
  StochasticSetup st{kWidth, kHeight, 4, 2, 12345u, 1};
  const auto one = stochastic_model(coverage, centre, bg, st);
  SlabSetup sl{kWidth, kHeight, 2, 8, 678u, 1};
  const auto slab_one = slab_model(coverage, bg, sl);
  for (unsigned threads : {2u, 3u, 5u}) {
    st.threads = threads;
    sl.threads = threads;
    EXPECT_TRUE(same_bits(one, stochastic_model(coverage, centre, bg, st))) << threads;
    EXPECT_TRUE(same_bits(slab_one, slab_model(coverage, bg, sl))) << threads;
  }
}

namespace {
SceneDesc planes_scene(const std::string& count, const std::string& background = "[1, 1, 1]") {
  return parse_scene("s.json", R"({
  "background": )" + background + R"(,
  "materials": { "glass": { "colour": [0.5, 0.5, 0.5], "alpha": 0.5 } },
  "objects": [ { "generator": "planes", "material": "glass", "params": { "count": )" +
                                   count + R"(, "depth": 1 } } ],
  "views": { "fwd": { "eye": [0, 0, 3], "order": "front-to-back" }, "side": { "eye": [0.5, 0, 3] } }
})");
}
}  // namespace

// The key names everything the reference reads, so no parameter can hit another's entry; the shared
// reference is the one computed directly.
TEST(SharedGeometricReference, TheKeyChangesWithEverythingTheReferenceReads) {
  const SceneDesc s = planes_scene("3");
  const View fwd = s.view("fwd");
  const glm::vec2 nf(0.1f, 10.0f);
  const std::string key = geometric_reference_key(s, fwd, Detail::Full, nf, 16, 8, FragColour::RGBA8);
  ASSERT_FALSE(key.empty());
  EXPECT_EQ(key, geometric_reference_key(planes_scene("3"), fwd, Detail::Full, nf, 16, 8, FragColour::RGBA8));
  View moved = fwd;
  moved.fov_deg += 1e-3f;
  for (const std::string& other :
       {geometric_reference_key(planes_scene("4"), fwd, Detail::Full, nf, 16, 8, FragColour::RGBA8),
        geometric_reference_key(planes_scene("3", "[1, 1, 0.999]"), fwd, Detail::Full, nf, 16, 8, FragColour::RGBA8),
        geometric_reference_key(s, s.view("side"), Detail::Full, nf, 16, 8, FragColour::RGBA8),
        geometric_reference_key(s, moved, Detail::Full, nf, 16, 8, FragColour::RGBA8),
        geometric_reference_key(s, fwd, Detail::Full, {0.1f, 9.0f}, 16, 8, FragColour::RGBA8),
        geometric_reference_key(s, fwd, Detail::Full, nf, 8, 16, FragColour::RGBA8),
        geometric_reference_key(s, fwd, Detail::Full, nf, 16, 8, FragColour::RGBA16F)})
    EXPECT_NE(other, key);

  SharedCache cache;
  auto a = shared_geometric_reference(&cache, s, fwd, Detail::Full, nf, 16, 8, FragColour::RGBA8);
  auto b = shared_geometric_reference(&cache, s, fwd, Detail::Full, nf, 16, 8, FragColour::RGBA8);
  auto c = shared_geometric_reference(&cache, s, fwd, Detail::Full, nf, 16, 8, FragColour::RGBA32F);
  ASSERT_TRUE(a && c);
  EXPECT_EQ(a.get(), b.get());
  EXPECT_NE(a.get(), c.get());
  EXPECT_EQ(cache.hits(), 1u);
  auto direct = geometric_reference(s, fwd, Detail::Full, nf, 16, 8, FragColour::RGBA8);
  ASSERT_TRUE(direct.has_value());
  EXPECT_TRUE(same_bits(a->exact, direct->exact));
  EXPECT_TRUE(same_bits(a->quantised, direct->quantised));
  EXPECT_EQ(a->layers, direct->layers);
  EXPECT_EQ(a->ambiguous, direct->ambiguous);
  EXPECT_EQ(a->ambiguous_pixels, direct->ambiguous_pixels);
}

}  // namespace oitbench::oit
