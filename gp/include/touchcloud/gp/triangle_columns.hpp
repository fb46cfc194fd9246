// Work over the columns of an n x n lower triangle, on two threads: column j
// holds n - j entries, so the split falls where each side gets half of them.
// The columns are independent; a caller that sums over them does so in
// column order afterwards, so results do not depend on the split.
#pragma once

#include <cmath>

#include <Eigen/Core>

#include "touchcloud/gp/two_threads.hpp"

namespace touchcloud::gp {

// Calls body(first, last) on column ranges covering [0, n): [0, split) on a
// second thread and [split, n) on this one, or [0, n) here for small n
// (n (n + 1) / 2 entries below kTwoThreadWork: n < 256).
template <class Body>
void for_triangle_columns(Eigen::Index n, Body body) {
  // Columns [0, s) hold n s - s^2 / 2 entries: half of n^2 / 2 at s = n (1 - 1/sqrt 2).
  on_two_threads(n, static_cast<Eigen::Index>(static_cast<double>(n) * (1.0 - std::sqrt(0.5))), n * (n + 1) / 2, body);
}

}  // namespace touchcloud::gp
