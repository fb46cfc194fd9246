// Splits a range of independent items between this thread and one more.
#pragma once

#include <future>

#include <Eigen/Core>

namespace touchcloud::gp {

// Calls body(0, split) on a second thread and body(split, n) on this one.
template <class Body>
void on_two_threads(Eigen::Index n, Eigen::Index split, Body body) {
  std::future<void> first = std::async(std::launch::async, [&] { body(Eigen::Index{0}, split); });
  body(split, n);
  first.get();
}

}  // namespace touchcloud::gp
