#include "touchcloud/calibration/normal_chart.hpp"

#include <cmath>

#include <Eigen/Geometry>

#include "touchcloud/error.hpp"

namespace touchcloud::calibration {

NormalChart::NormalChart(const Eigen::Vector3d& reference_normal) {
  if (!reference_normal.allFinite() || reference_normal.norm() < 1e-12)
    throw InputError("plate normal: must be a finite, non-zero vector");
  n0_ = reference_normal.normalized();
  // Any tangent basis will do; start from the axis least aligned with n0.
  Eigen::Index axis;
  n0_.cwiseAbs().minCoeff(&axis);
  e1_ = n0_.cross(Eigen::Vector3d::Unit(axis)).normalized();
  e2_ = n0_.cross(e1_);
}

Eigen::Vector3d NormalChart::normal(double a_rad, double b_rad) const {
  const double t = std::hypot(a_rad, b_rad);
  // sin(t)/t to second order below 1e-8: exact in double precision there.
  const double sinc = t < 1e-8 ? 1.0 - t * t / 6.0 : std::sin(t) / t;
  return (std::cos(t) * n0_ + sinc * (a_rad * e1_ + b_rad * e2_)).normalized();
}

Eigen::Vector2d NormalChart::coordinates(const Eigen::Vector3d& normal) const {
  const Eigen::Vector3d n = normal.normalized();
  const Eigen::Vector2d tangent(n.dot(e1_), n.dot(e2_));
  const double s = tangent.norm();
  if (s < 1e-300) return Eigen::Vector2d::Zero();
  return std::atan2(s, n.dot(n0_)) / s * tangent;
}

}  // namespace touchcloud::calibration
