#include "touchcloud/optics/refractive_plate.hpp"

#include <cmath>

#include "config_check.hpp"

namespace touchcloud::optics {

void RefractivePlate::validate(const char* what) const {
  ConfigCheck check(what);
  const double length = normal.norm();
  check.require(normal.allFinite() && std::abs(length - 1.0) <= 1e-9, "normal",
                "(" + format_number(normal.x()) + ", " + format_number(normal.y()) + ", " +
                    format_number(normal.z()) + ") of length " + format_number(length),
                "a unit vector (length within 1e-9 of 1)");
  check.require(std::isfinite(distance_mm) && distance_mm > 0, "distance_mm", distance_mm, "finite and > 0");
  check.require(std::isfinite(thickness_mm) && thickness_mm >= 0, "thickness_mm", thickness_mm,
                "finite and >= 0");
  check.require(std::isfinite(mu_air) && mu_air >= 1, "mu_air", mu_air, "finite and >= 1");
  check.require(std::isfinite(mu_acrylic) && mu_acrylic >= 1, "mu_acrylic", mu_acrylic, "finite and >= 1");
  check.require(std::isfinite(mu_silicone) && mu_silicone >= 1, "mu_silicone", mu_silicone, "finite and >= 1");
  check.throw_if_failed();
}

RefractivePlate RefractivePlate::expressed_in(const Eigen::Isometry3d& other_from_this) const {
  // n . X = d with X = R^T (X' - t)  <=>  (R n) . X' = d + (R n) . t
  RefractivePlate plate = *this;
  plate.normal = other_from_this.linear() * normal;
  plate.distance_mm = distance_mm + plate.normal.dot(other_from_this.translation());
  return plate;
}

}  // namespace touchcloud::optics
