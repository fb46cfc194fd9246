#include "touchcloud/optics/pinhole_camera.hpp"

#include <cmath>
#include <limits>

#include <Eigen/LU>

#include "config_check.hpp"

namespace touchcloud::optics {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// d(r L(r^2))/dr as a function of u = r^2: 1 + 3 k1 u + 5 k2 u^2 + 7 k3 u^3.
double radial_slope(const BrownConrady& d, double u) {
  return 1.0 + u * (3.0 * d.k1 + u * (5.0 * d.k2 + u * 7.0 * d.k3));
}

// Smallest u > 0 where the radial map stops increasing. Beyond it the lens
// model folds back and no longer describes a real lens. Scanned on a
// geometric grid up to u = 1e4 (89.4 deg off axis), then bisected.
double find_fold_radius2(const BrownConrady& d) {
  if (radial_slope(d, 0) <= 0) return 0;
  double prev = 0;
  for (double u = 1e-6; u <= 1e4; u *= 1.01) {
    if (radial_slope(d, u) <= 0) {
      double lo = prev, hi = u;
      for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) {
        const double mid = 0.5 * (lo + hi);
        (radial_slope(d, mid) > 0 ? lo : hi) = mid;
      }
      return lo;
    }
    prev = u;
  }
  return kInfinity;
}

}  // namespace

void CameraIntrinsics::validate(const char* what) const {
  ConfigCheck check(what);
  check.require(width_px > 0, "width_px", width_px, "> 0");
  check.require(height_px > 0, "height_px", height_px, "> 0");
  check.require(std::isfinite(fx_px) && fx_px > 0, "fx_px", fx_px, "finite and > 0");
  check.require(std::isfinite(fy_px) && fy_px > 0, "fy_px", fy_px, "finite and > 0");
  check.require(std::isfinite(cx_px), "cx_px", cx_px, "finite");
  check.require(std::isfinite(cy_px), "cy_px", cy_px, "finite");
  const BrownConrady& d = distortion;
  check.require(std::isfinite(d.k1), "distortion.k1", d.k1, "finite");
  check.require(std::isfinite(d.k2), "distortion.k2", d.k2, "finite");
  check.require(std::isfinite(d.p1), "distortion.p1", d.p1, "finite");
  check.require(std::isfinite(d.p2), "distortion.p2", d.p2, "finite");
  check.require(std::isfinite(d.k3), "distortion.k3", d.k3, "finite");
  check.throw_if_failed();
}

PinholeCamera::PinholeCamera(const CameraIntrinsics& intrinsics) : intrinsics_(intrinsics) {
  intrinsics_.validate();
  fold_radius2_ = find_fold_radius2(intrinsics_.distortion);
}

Eigen::Vector2d PinholeCamera::distort(const Eigen::Vector2d& undistorted) const {
  const BrownConrady& d = intrinsics_.distortion;
  const double x = undistorted.x(), y = undistorted.y();
  const double r2 = x * x + y * y;
  const double radial = 1.0 + r2 * (d.k1 + r2 * (d.k2 + r2 * d.k3));
  return {x * radial + 2.0 * d.p1 * x * y + d.p2 * (r2 + 2.0 * x * x),
          y * radial + d.p1 * (r2 + 2.0 * y * y) + 2.0 * d.p2 * x * y};
}

TraceStatus PinholeCamera::undistort(const Eigen::Vector2d& distorted, Eigen::Vector2d& undistorted) const {
  const BrownConrady& d = intrinsics_.distortion;
  // Newton on distort(x) = distorted: quadratic where OpenCV's fixed-point
  // iteration is linear, and it reaches the same root.
  Eigen::Vector2d x = distorted;
  bool converged = false;
  for (int iteration = 0; iteration < 50 && !converged; ++iteration) {
    const double r2 = x.squaredNorm();
    const double radial = 1.0 + r2 * (d.k1 + r2 * (d.k2 + r2 * d.k3));
    const double radial_d = d.k1 + r2 * (2.0 * d.k2 + r2 * 3.0 * d.k3);  // dL/d(r^2)
    const double xy = x.x() * x.y();
    Eigen::Matrix2d jacobian;
    jacobian << radial + 2.0 * x.x() * x.x() * radial_d + 2.0 * d.p1 * x.y() + 6.0 * d.p2 * x.x(),
        2.0 * xy * radial_d + 2.0 * d.p1 * x.x() + 2.0 * d.p2 * x.y(),
        2.0 * xy * radial_d + 2.0 * d.p1 * x.x() + 2.0 * d.p2 * x.y(),
        radial + 2.0 * x.y() * x.y() * radial_d + 6.0 * d.p1 * x.y() + 2.0 * d.p2 * x.x();
    const double det = jacobian.determinant();
    if (!(std::abs(det) > 1e-12)) break;
    const Eigen::Vector2d step = jacobian.inverse() * (distort(x) - distorted);
    x -= step;
    if (!x.allFinite()) break;
    converged = step.norm() <= 1e-15 * (1.0 + x.norm());
  }
  const bool on_fold_free_part = x.squaredNorm() <= fold_radius2_;
  const bool solves = x.allFinite() && (distort(x) - distorted).norm() <= 1e-13 * (1.0 + distorted.norm());
  if (!(on_fold_free_part && solves)) return TraceStatus::UndistortionFailed;
  undistorted = x;
  return TraceStatus::Ok;
}

PixelProjection PinholeCamera::project(const Eigen::Vector3d& point_camera) const {
  if (!(point_camera.z() > 0)) return {TraceStatus::BehindCamera, Eigen::Vector2d::Zero()};
  const Eigen::Vector2d normalised = point_camera.head<2>() / point_camera.z();
  if (!(normalised.squaredNorm() <= fold_radius2_)) return {TraceStatus::OutOfView, Eigen::Vector2d::Zero()};
  const Eigen::Vector2d distorted = distort(normalised);
  const CameraIntrinsics& k = intrinsics_;
  const Eigen::Vector2d pixel(k.fx_px * distorted.x() + k.cx_px, k.fy_px * distorted.y() + k.cy_px);
  return {in_view(pixel) ? TraceStatus::Ok : TraceStatus::OutOfView, pixel};
}

PixelDirection PinholeCamera::back_project(const Eigen::Vector2d& pixel_px) const {
  const CameraIntrinsics& k = intrinsics_;
  const Eigen::Vector2d distorted((pixel_px.x() - k.cx_px) / k.fx_px, (pixel_px.y() - k.cy_px) / k.fy_px);
  Eigen::Vector2d undistorted;
  if (!distorted.allFinite() || undistort(distorted, undistorted) != TraceStatus::Ok)
    return {TraceStatus::UndistortionFailed, Eigen::Vector3d::Zero()};
  return {TraceStatus::Ok, Eigen::Vector3d(undistorted.x(), undistorted.y(), 1.0).normalized()};
}

bool PinholeCamera::in_view(const Eigen::Vector2d& pixel_px) const {
  return pixel_px.x() >= -0.5 && pixel_px.x() < intrinsics_.width_px - 0.5 && pixel_px.y() >= -0.5 &&
         pixel_px.y() < intrinsics_.height_px - 0.5;
}

}  // namespace touchcloud::optics
