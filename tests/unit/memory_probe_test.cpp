// The host memory probe (core/memory_probe.hpp): its chase is one cycle through every line (a shorter loop
// would sit in the cache and measure nothing), the same cycle in every run, and a latency is a positive,
// finite number of nanoseconds that a buffer in the L1 makes much smaller than one past the last-level cache.
#include "core/memory_probe.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace oitbench {
namespace {

TEST(MemoryProbe, TheChaseIsOneCycleThroughEveryLine) {
  for (size_t bytes : {size_t{128}, size_t{64} * 1000, size_t{1} << 20}) {
    MemoryProbe probe(bytes);
    const size_t n = probe.lines();
    ASSERT_EQ(n, bytes / MemoryProbe::kLineBytes);
    std::vector<char> seen(n, 0);
    uint32_t at = 0;
    for (size_t i = 0; i < n; ++i) {
      ASSERT_LT(at, n);
      ASSERT_FALSE(seen[at]) << "line " << at << " visited twice after " << i << " steps of " << n;
      seen[at] = 1;
      at = probe.next(at);
    }
    EXPECT_EQ(at, 0u) << "the chase returns to its start after every line";
  }
}

TEST(MemoryProbe, EveryRunChasesTheSameCycle) {
  MemoryProbe a(size_t{1} << 16), b(size_t{1} << 16);
  for (uint32_t i = 0; i < a.lines(); ++i) ASSERT_EQ(a.next(i), b.next(i));
  // and it is not the identity order a prefetcher would follow
  size_t sequential = 0;
  for (uint32_t i = 0; i < a.lines(); ++i) sequential += a.next(i) == (i + 1) % a.lines();
  EXPECT_LT(sequential, a.lines() / 10);
}

TEST(MemoryProbe, ALatencyIsPositiveAndTheL1IsFasterThanMemory) {
  MemoryProbe small(size_t{16} << 10), large;  // 16 KiB: the L1; 64 MiB: memory
  double best_small = 1e9, best_large = 1e9;
  for (int i = 0; i < 5; ++i) {
    const double s = small.latency_ns(20000), l = large.latency_ns(4000);
    ASSERT_TRUE(std::isfinite(s) && s > 0) << s;
    ASSERT_TRUE(std::isfinite(l) && l > 0) << l;
    best_small = std::min(best_small, s);
    best_large = std::min(best_large, l);
  }
  // An L1 hit is a few ns, a miss to memory tens to hundreds: a factor of 3 holds on any host, loaded or not.
  EXPECT_GT(best_large, 3 * best_small) << "L1 " << best_small << " ns, memory " << best_large << " ns";
}

}  // namespace
}  // namespace oitbench
