#include "touchcloud/optics/ray_triangulation.hpp"

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "config_check.hpp"
#include "touchcloud/error.hpp"

namespace touchcloud::optics {

void RayTriangulationOptions::validate(const char* what) const {
  // Checked on every triangulation: the passing case allocates nothing.
  const bool angle_ok = min_ray_angle_rad > 0 && min_ray_angle_rad < std::numbers::pi / 2;
  const bool tolerance_ok = std::isfinite(behind_tolerance_mm) && behind_tolerance_mm >= 0;
  if (angle_ok && tolerance_ok) return;
  ConfigCheck check(what);
  check.require(angle_ok, "min_ray_angle_rad", min_ray_angle_rad, "in (0, pi/2)");
  check.require(tolerance_ok, "behind_tolerance_mm", behind_tolerance_mm, "finite and >= 0");
  check.throw_if_failed();
}

const char* to_string(TriangulationStatus status) {
  switch (status) {
    case TriangulationStatus::Ok: return "ok";
    case TriangulationStatus::Degenerate: return "degenerate (rays nearly parallel)";
    case TriangulationStatus::BehindRayOrigin: return "behind a ray's origin";
    case TriangulationStatus::LeftRayInvalid: return "left ray invalid";
    case TriangulationStatus::RightRayInvalid: return "right ray invalid";
  }
  return "?";
}

namespace {

// a b - c d to within 1.5 ulp of the result (Kahan), where the plain form
// loses all digits for nearly equal products.
double difference_of_products(double a, double b, double c, double d) {
  const double cd = c * d;
  const double cd_error = std::fma(-c, d, cd);
  return std::fma(a, b, -cd) + cd_error;
}

// u x v with each component accurate relative to itself: for nearly parallel
// rays |m| keeps its digits (and with them the gap and the point).
Eigen::Vector3d accurate_cross(const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
  return {difference_of_products(u.y(), v.z(), u.z(), v.y()),
          difference_of_products(u.z(), v.x(), u.x(), v.z()),
          difference_of_products(u.x(), v.y(), u.y(), v.x())};
}

}  // namespace

TriangulatedPoint triangulate_rays(const Eigen::Vector3d& origin_left, const Eigen::Vector3d& direction_left,
                                   const Eigen::Vector3d& origin_right, const Eigen::Vector3d& direction_right,
                                   const RayTriangulationOptions& options) {
  options.validate();
  if (!(origin_left.allFinite() && direction_left.allFinite() && origin_right.allFinite() &&
        direction_right.allFinite()))
    throw InputError("triangulate_rays: a ray origin or direction is not finite");
  TriangulatedPoint out;
  const double length_left = direction_left.norm(), length_right = direction_right.norm();
  if (!(length_left > 0 && length_right > 0)) {
    out.status = TriangulationStatus::Degenerate;
    return out;
  }
  const Eigen::Vector3d d_left = direction_left / length_left;
  const Eigen::Vector3d d_right = direction_right / length_right;
  const Eigen::Vector3d w = origin_right - origin_left;
  const Eigen::Vector3d m = accurate_cross(d_left, d_right);
  const double m_norm = m.norm();  // sin of the angle between the rays

  if (!(m_norm >= std::sin(options.min_ray_angle_rad))) {
    out.status = TriangulationStatus::Degenerate;
    out.gap_mm = w.cross(d_left).norm();  // distance between (nearly) parallel lines
    return out;
  }
  const double m_norm2 = m_norm * m_norm;
  out.s_left_mm = w.cross(d_right).dot(m) / m_norm2;
  out.s_right_mm = w.cross(d_left).dot(m) / m_norm2;
  out.gap_mm = std::abs(w.dot(m)) / m_norm;
  out.point_mm = 0.5 * ((origin_left + out.s_left_mm * d_left) + (origin_right + out.s_right_mm * d_right));
  if (out.s_left_mm < -options.behind_tolerance_mm || out.s_right_mm < -options.behind_tolerance_mm)
    out.status = TriangulationStatus::BehindRayOrigin;
  return out;
}

}  // namespace touchcloud::optics
