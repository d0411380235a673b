#include "core/memory_probe.hpp"

#include <algorithm>
#include <stdexcept>

namespace oitbench {

namespace {

uint64_t splitmix64(uint64_t& state) {
  uint64_t z = (state += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

}  // namespace

MemoryProbe::MemoryProbe(size_t bytes) {
  const size_t n = std::max<size_t>(bytes / kLineBytes, 2);
  if (n > UINT32_MAX) throw std::invalid_argument("memory probe: at most 2^32 lines");
  // A random visiting order (Fisher-Yates); each line points at the next in it and the last at the first:
  // one cycle through every line, so the chase never settles into a short loop the cache could hold, and
  // the next line is any of the buffer's lines, not one a prefetcher would guess.
  lines_.resize(n);  // the large allocation first: a refused one costs nothing else
  std::vector<uint32_t> order(n);
  for (size_t i = 0; i < n; ++i) order[i] = static_cast<uint32_t>(i);
  uint64_t state = 0x6f6974626e656863ull;  // fixed: every run chases the same cycle
  for (size_t i = n - 1; i > 0; --i) std::swap(order[i], order[splitmix64(state) % (i + 1)]);
  // Linked line by line (each line's place in the order, then its successor): sequential writes to the
  // lines, random ones only within the order's 4 bytes a line.
  std::vector<uint32_t> place(n);
  for (size_t i = 0; i < n; ++i) place[order[i]] = static_cast<uint32_t>(i);
  for (size_t j = 0; j < n; ++j) lines_[j].next = order[(place[j] + 1) % n];
}

double MemoryProbe::latency_ns(int loads) {
  loads = std::max(loads, 1);
  // One load a page first, untimed: the page tables' lines come back into the caches, so the chase measures
  // the memory and not what the work before it evicted (a large case's round evicts them, a small one's not).
  constexpr size_t kLinesPerPage = 4096 / kLineBytes;
  uint64_t touched = 0;
  for (size_t i = 0; i < lines_.size(); i += kLinesPerPage) touched += lines_[i].next;
  sink_ += touched;
  uint32_t at = at_;
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < loads; ++i) at = lines_[at].next;
  const auto end = std::chrono::steady_clock::now();
  at_ = at;
  sink_ += at;
  return std::chrono::duration<double, std::nano>(end - start).count() / loads;
}

}  // namespace oitbench
