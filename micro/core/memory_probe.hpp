#pragma once
// The host's memory latency, measured between a case's timed rounds (the host_mem_ns columns): a
// dependent-load chase through a random cycle of cache lines in a buffer larger than most CPUs' last-level
// cache, so every load waits for memory (and, with 4 KiB pages, for a page walk), as a linked-list
// traversal does. On a software renderer the GPU's memory is this memory: a resolve that walks lists
// slows when it does, while a sort in local arrays (in the L1) does not. On a shared host the latency is
// not constant: another tenant's traffic raises it for seconds at a time, and rows measured then show it
// (docs/drivers.md, "The host difference").
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace oitbench {

class MemoryProbe {
 public:
  static constexpr size_t kLineBytes = 64;
  static constexpr size_t kDefaultBytes = size_t{64} << 20;  // 64 MiB: past a 32 MiB L3 twice over
  static constexpr int kDefaultLoads = 4000;                 // about 1 ms at 200 ns a load

  // Builds the cycle (one visit per line, in a fixed pseudo-random order): about 0.05 s for 64 MiB, and
  // 1/8 of `bytes` more while it builds. Throws std::bad_alloc where the memory is refused.
  explicit MemoryProbe(size_t bytes = kDefaultBytes);
  MemoryProbe(const MemoryProbe&) = delete;
  MemoryProbe& operator=(const MemoryProbe&) = delete;

  // Nanoseconds per load over `loads` dependent loads, continuing the cycle where the last call stopped.
  double latency_ns(int loads = kDefaultLoads);
  size_t lines() const { return lines_.size(); }
  // The line after `i` in the cycle (tests: the cycle visits every line once).
  uint32_t next(uint32_t i) const { return lines_[i].next; }

 private:
  struct alignas(kLineBytes) Line {
    uint32_t next = 0;
  };
  std::vector<Line> lines_;
  uint32_t at_ = 0;
  uint64_t sink_ = 0;  // keeps the chase from being optimised away
};

}  // namespace oitbench
