#pragma once
// Per-pixel CPU work (references, the approximate techniques' models) spread over the cores by image
// rows. Only for work outside the timed regions: it takes every core. `work(thread, pixel)` must write
// only its pixel's results and its own thread's scratch (index `thread` < the returned thread count), so
// the results do not depend on the number of threads.
#include <algorithm>
#include <cstddef>
#include <thread>
#include <vector>

namespace oitbench {

// The threads parallel_rows() uses for `rows` rows: `threads` (0: every core), at most one a row.
inline unsigned parallel_row_threads(size_t rows, unsigned threads = 0) {
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  return static_cast<unsigned>(std::clamp<size_t>(threads, 1, std::max<size_t>(rows, 1)));
}

// Calls work(thread, pixel) for every pixel of `pixels` in rows of `row` pixels, row r on thread
// r % threads (interleaved rows even out a scene's dense and empty bands); threads from
// parallel_row_threads(rows, threads).
template <class Work>
void parallel_rows(size_t pixels, size_t row, unsigned threads, Work work) {
  row = std::max<size_t>(row, 1);
  const size_t rows = (pixels + row - 1) / row;
  threads = parallel_row_threads(rows, threads);
  auto part = [&](unsigned t) {
    for (size_t r = t; r < rows; r += threads)
      for (size_t p = r * row; p < std::min(pixels, (r + 1) * row); ++p) work(t, p);
  };
  if (threads == 1) {
    part(0);
    return;
  }
  std::vector<std::thread> pool;
  pool.reserve(threads - 1);
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(part, t);
  part(0);
  for (auto& th : pool) th.join();
}

}  // namespace oitbench
