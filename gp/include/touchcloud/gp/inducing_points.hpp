// Inducing points for the sparse VFE surface: a farthest-point subset of the
// touches' (x, y). Each pick is the training point farthest from those picked
// so far, so the set covers the touched area evenly at every size, and a
// larger set contains a smaller one (the VFE bound grows along such nested
// sets). O(n m).
#pragma once

#include <vector>

#include <Eigen/Core>

namespace touchcloud::gp {

// Row indices into xy_mm of min(m, n) points, starting from row `first`
// (the caller's seeded choice). All n rows, in order, when m >= n. Ties go to
// the lower row index, so the result is deterministic.
std::vector<Eigen::Index> farthest_point_subset(const Eigen::MatrixX2d& xy_mm, Eigen::Index m, Eigen::Index first);

}  // namespace touchcloud::gp
