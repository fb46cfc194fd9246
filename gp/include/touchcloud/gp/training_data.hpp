// Checking and centring tactile points before they reach the GP. The GP works
// on coordinates relative to a fixed centre so that kernel distances keep
// their precision when points sit far from the origin (robot base frame).
#pragma once

#include <string>

#include <Eigen/Core>

namespace touchcloud::gp {

// Offsets subtracted from x, y (middle of the bounding box) and z (mean).
struct Centring {
  double x_mm = 0.0, y_mm = 0.0, z_mm = 0.0;
};
Centring centring_of(const Eigen::MatrixX2d& xy_mm, const Eigen::VectorXd& z_mm);

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
