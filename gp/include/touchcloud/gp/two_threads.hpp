// Splits a range of independent items between this thread and one more,
// when there is enough work for a second thread to pay.
#pragma once

#include <future>

#include <Eigen/Core>

namespace touchcloud::gp {

// Below this much work (kernel values, triangle entries) a second thread
// costs more than it saves.
inline constexpr Eigen::Index kTwoThreadWork = Eigen::Index{1} << 15;

// Calls body(first, last) on ranges covering [0, n): with at least
// kTwoThreadWork of `work` in all, [0, split) on a second thread and
// [split, n) on this one; with less, [0, n) here.
template <class Body>
void on_two_threads(Eigen::Index n, Eigen::Index split, Eigen::Index work, Body body) {
  if (work < kTwoThreadWork) {
    body(Eigen::Index{0}, n);
    return;
  }
  std::future<void> first = std::async(std::launch::async, [&] { body(Eigen::Index{0}, split); });
  body(split, n);
  first.get();
}

}  // namespace touchcloud::gp
