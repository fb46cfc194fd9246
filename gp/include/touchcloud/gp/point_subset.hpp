// Subsets of the training points for cheaper hyperparameter selection. Points
// arrive touch by touch, so consecutive points are parts of one touch; a
// subset made of runs of consecutive points spread evenly over the data keeps
// the touches' point density, which the lengthscale and noise depend on,
// where an evenly strided subset would thin every patch and read its fine
// relief as noise. (Points in no particular order give a random subset
// either way.)
#pragma once

#include <utility>

#include <Eigen/Core>

namespace touchcloud::gp {

// `size` points (all when size >= n) in `runs` runs of consecutive points
// starting at evenly spaced positions, in data order.
std::pair<Eigen::MatrixX2d, Eigen::VectorXd> subset_of_runs(const Eigen::MatrixX2d& xy_mm, const Eigen::VectorXd& z_mm,
                                                            Eigen::Index size, Eigen::Index runs);

}  // namespace touchcloud::gp
