// Splits a range of work items over threads: contiguous blocks, the first on
// the calling thread, exceptions carried back to the caller.
#pragma once

#include <algorithm>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace touchcloud {

// The number of threads to use: `requested`, or every hardware thread for 0.
inline int resolve_threads(int requested) {
  if (requested > 0) return requested;
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

// Runs body(begin, end) on `threads` contiguous blocks of [0, n). Blocks
// smaller than `min_block` items are merged, so tiny inputs stay on one thread.
template <class Body>
void for_each_block(std::size_t n, int threads, std::size_t min_block, Body body) {
  std::size_t blocks = std::max<std::size_t>(1, std::min<std::size_t>(threads, n / std::max<std::size_t>(min_block, 1)));
  if (blocks <= 1) {
    body(std::size_t{0}, n);
    return;
  }
  std::vector<std::exception_ptr> errors(blocks);
  std::vector<std::thread> workers;
  workers.reserve(blocks - 1);
  const auto run = [&](std::size_t b) {
    try {
      body(n * b / blocks, n * (b + 1) / blocks);
    } catch (...) {
      errors[b] = std::current_exception();
    }
  };
  for (std::size_t b = 1; b < blocks; ++b) workers.emplace_back(run, b);
  run(0);
  for (auto& w : workers) w.join();
  for (auto& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace touchcloud
