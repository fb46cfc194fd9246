// Checking and centring tactile points before they reach the GP. The GP works
// on coordinates relative to a fixed centre so that kernel distances keep
// their precision when points sit far from the origin (robot base frame).
#pragma once

#include <string>

#include <Eigen/Core>

namespace touchcloud::gp {

// Offsets subtracted from x, y (middle of the bounding box) and z (the GP's
// constant prior mean, which the surface returns to far from its data).
struct Centring {
  double x_mm = 0.0, y_mm = 0.0, z_mm = 0.0;
};
// The z offset: the data's mean, or its median (a relief on a plate: the
// level most touches land on, so an unreached valley beside a tall part
// returns to the plate instead of hanging at the mean height).
enum class PriorMean { mean, median };
Centring centring_of(const Eigen::MatrixX2d& xy_mm, const Eigen::VectorXd& z_mm, PriorMean level = PriorMean::mean);

// InputError unless every coordinate is finite; `what` names the point set
// ("training point", "query point") in the message.
void check_finite(const Eigen::MatrixX2d& xy_mm, const std::string& what);
// Also checks z and that it has one value per (x, y) row.
void check_training(const Eigen::MatrixX2d& xy_mm, const Eigen::VectorXd& z_mm, const std::string& what);

// Coordinates minus the centre, as separate columns (vectorised distances).
struct CentredXy {
  Eigen::VectorXd x, y;
};
CentredXy centre(const Eigen::MatrixX2d& xy_mm, const Centring& c);

}  // namespace touchcloud::gp
