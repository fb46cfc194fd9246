// A 2-angle chart on the unit sphere around a reference normal n0: the
// exponential map n(a, b) = cos(t) n0 + sin(t) / t (a e1 + b e2), t = |(a, b)|
// in radians. Unlike (z_x, z_y) it stays regular at any tilt of n0.
#pragma once

#include <Eigen/Core>

namespace touchcloud::calibration {

class NormalChart {
 public:
  explicit NormalChart(const Eigen::Vector3d& reference_normal);  // normalised; InputError if zero

  Eigen::Vector3d normal(double a_rad, double b_rad) const;
  // The chart coordinates of a unit normal (the inverse, for |angle to n0| < pi).
  Eigen::Vector2d coordinates(const Eigen::Vector3d& normal) const;
  const Eigen::Vector3d& reference() const { return n0_; }

 private:
  Eigen::Vector3d n0_, e1_, e2_;
};

}  // namespace touchcloud::calibration
