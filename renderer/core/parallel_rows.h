// Row-parallel loops for functions that map a whole image (FLIP, view images, unpacking a streamed
// frame's texels): f(begin, end) over row ranges on up to the machine's cores, inline for small images.
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <thread>
#include <vector>

namespace gb {

template <class F>
void parallelRows(uint32_t rows, size_t pixels, const F& f) {
  const unsigned n = pixels < 32768 ? 1u : std::clamp(std::thread::hardware_concurrency(), 1u, 8u);
  if (n == 1) return f(0u, rows);
  std::vector<std::thread> threads;
  for (unsigned i = 1; i < n; ++i) threads.emplace_back(f, rows * i / n, rows * (i + 1) / n);
  f(0u, rows / n);
  for (std::thread& t : threads) t.join();
}

}  // namespace gb
