// Small seeded data sets for the GP tests: points on a smooth height field,
// with coordinates rounded to multiples of 2^-10 mm so that adding a large
// offset (base frame) is exact and any change in a prediction is the GP's.
#pragma once

#include <algorithm>
#include <cmath>
#include <random>

#include <Eigen/Core>

namespace touchcloud::gp::test {

inline double dyadic(double v) { return std::ldexp(std::round(std::ldexp(v, 10)), -10); }

// A gentle surface, heights of a few mm over a 60 mm patch.
inline double smooth_height_mm(double x, double y) { return 3.0 * std::sin(x / 9.0) * std::cos(y / 13.0) + 0.02 * x; }

inline Eigen::MatrixX2d random_xy(Eigen::Index n, unsigned seed, double extent_mm = 60.0) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, extent_mm);
  Eigen::MatrixX2d xy(n, 2);
  for (Eigen::Index i = 0; i < n; ++i) {
    xy(i, 0) = dyadic(u(rng));
    xy(i, 1) = dyadic(u(rng));
  }
  return xy;
}

// Heights on the surface plus Gaussian noise of `noise_sd_mm`.
inline Eigen::VectorXd heights(const Eigen::MatrixX2d& xy, double noise_sd_mm = 0.0, unsigned seed = 7) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  Eigen::VectorXd z(xy.rows());
  for (Eigen::Index i = 0; i < xy.rows(); ++i) z[i] = smooth_height_mm(xy(i, 0), xy(i, 1)) + noise_sd_mm * noise(rng);
  return z;
}

// An nx x ny grid over [lo, hi]^2.
inline Eigen::MatrixX2d grid_xy(Eigen::Index nx, Eigen::Index ny, double lo, double hi) {
  Eigen::MatrixX2d xy(nx * ny, 2);
  for (Eigen::Index i = 0; i < nx; ++i)
    for (Eigen::Index j = 0; j < ny; ++j) {
      xy(i * ny + j, 0) = lo + (hi - lo) * static_cast<double>(i) / static_cast<double>(std::max<Eigen::Index>(nx - 1, 1));
      xy(i * ny + j, 1) = lo + (hi - lo) * static_cast<double>(j) / static_cast<double>(std::max<Eigen::Index>(ny - 1, 1));
    }
  return xy;
}

inline Eigen::MatrixX2d one_point(double x, double y) {
  Eigen::MatrixX2d p(1, 2);
  p << x, y;
  return p;
}

inline double max_relative_difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / std::max(1e-300, b.cwiseAbs().maxCoeff());
}

}  // namespace touchcloud::gp::test
