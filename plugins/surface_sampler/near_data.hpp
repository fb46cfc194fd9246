// The z range of the fitted points near each node of a regular lattice: a
// height-field check that the surface stays near what was measured beside
// it. The global z range of the data misses a local spike (a surface passing
// exactly through two touches' points 0.2 mm apart and 2 mm apart in z swung
// 12 mm off between them, well inside the object's z range).
#pragma once

#include <Eigen/Core>

#include "touchcloud/types/point_cloud.hpp"

namespace touchcloud::surface_sampler {

// lo(i, j), hi(i, j): the least and greatest z of the points within
// radius_mm of (xs[i], ys[j]) in (x, y); +inf and -inf where there is none.
struct NearDataRange {
  Eigen::MatrixXd lo, hi;
  bool has_data(Eigen::Index i, Eigen::Index j) const { return lo(i, j) <= hi(i, j); }
  // How far z lies outside [lo, hi] (0 inside; 0 where there is no data).
  double beyond(Eigen::Index i, Eigen::Index j, double z) const;
};

// xs and ys: evenly spaced and increasing (the sampler's lattice), at least
// two each. Throws InputError for a point with a non-finite coordinate.
NearDataRange near_data_range(const Eigen::VectorXd& xs, const Eigen::VectorXd& ys, const PointCloud& points,
                              double radius_mm);

}  // namespace touchcloud::surface_sampler
