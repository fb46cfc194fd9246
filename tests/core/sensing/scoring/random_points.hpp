// Seeded random points and brute-force nearest distances, the reference the
// KD-tree results are checked against.
#pragma once

#include <cmath>
#include <limits>
#include <random>

#include "touchcloud/scoring/nearest_point_index.hpp"

namespace touchcloud::test {

// `n` points in a box of side `side_mm`, rounded to float as a PCL cloud
// would hold them.
inline scoring::Points random_points(std::size_t n, double side_mm, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-0.5 * side_mm, 0.5 * side_mm);
  scoring::Points out(n);
  for (auto& p : out)
    p = Eigen::Vector3d(static_cast<float>(u(rng)), static_cast<float>(u(rng)), static_cast<float>(u(rng)));
  return out;
}

inline double brute_force_nearest(const Eigen::Vector3d& q, const scoring::Points& points) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& p : points) best = std::min(best, (p - q).squaredNorm());
  return std::sqrt(best);
}

inline double relative_error(double value, double reference) {
  return std::abs(value - reference) / std::max(std::abs(reference), 1e-300);
}

}  // namespace touchcloud::test
