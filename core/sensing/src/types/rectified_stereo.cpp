#include "touchcloud/types/rectified_stereo.hpp"

#include <cmath>

#include "optics/config_check.hpp"

namespace touchcloud {

Eigen::Matrix4d RectifiedStereo::q() const {
  // Z = fx b / (d - (cx_l - cx_r)), X = (x - cx_l) Z / fx, Y = (y - cy) Z / fy.
  const double shift = cx_left_px - cx_right_px;
  Eigen::Matrix4d q = Eigen::Matrix4d::Zero();
  q(0, 0) = 1.0;
  q(0, 3) = -cx_left_px;
  q(1, 1) = fx_px / fy_px;
  q(1, 3) = -cy_px * fx_px / fy_px;
  q(2, 3) = fx_px;
  q(3, 2) = 1.0 / baseline_mm;
  q(3, 3) = -shift / baseline_mm;
  return q;
}

void RectifiedStereo::validate(const char* what) const {
  optics::ConfigCheck check(what);
  check.require(width_px > 0, "width_px", width_px, "> 0");
  check.require(height_px > 0, "height_px", height_px, "> 0");
  check.require(std::isfinite(fx_px) && fx_px > 0, "fx_px", fx_px, "> 0 and finite");
  check.require(std::isfinite(fy_px) && fy_px > 0, "fy_px", fy_px, "> 0 and finite");
  check.require(std::isfinite(cx_left_px) && std::isfinite(cx_right_px) && std::isfinite(cy_px), "principal point",
                "non-finite", "finite");
  check.require(std::isfinite(baseline_mm) && baseline_mm > 0, "baseline_mm", baseline_mm, "> 0 and finite");
  check.throw_if_failed();
}

RectifiedStereo rectify_stereo_rig(const optics::StereoRig& rig, int width_px, int height_px) {
  const optics::CameraIntrinsics& left = rig.camera(optics::StereoSide::Left).intrinsics();
  if (width_px <= 0) width_px = left.width_px;
  if (height_px <= 0) height_px = left.height_px;
  // Fusiello's construction: x along the baseline, z the left optical axis
  // made orthogonal to it, y completing a right-handed frame.
  const Eigen::Vector3d baseline = rig.centre_mm(optics::StereoSide::Right);
  const Eigen::Vector3d x = baseline.normalized();
  const Eigen::Vector3d z = (Eigen::Vector3d::UnitZ() - x.z() * x).normalized();
  const Eigen::Vector3d y = z.cross(x);
  RectifiedStereo r;
  r.left_rect_from_left.row(0) = x.transpose();
  r.left_rect_from_left.row(1) = y.transpose();
  r.left_rect_from_left.row(2) = z.transpose();
  r.right_rect_from_right = r.left_rect_from_left * rig.right_from_left().linear().transpose();
  const double sx = static_cast<double>(width_px) / left.width_px, sy = static_cast<double>(height_px) / left.height_px;
  r.width_px = width_px;
  r.height_px = height_px;
  r.fx_px = left.fx_px * sx;
  r.fy_px = left.fy_px * sy;
  // Pixel centres: (0, 0) is the top-left pixel's centre at either size.
  r.cx_left_px = r.cx_right_px = (left.cx_px + 0.5) * sx - 0.5;
  r.cy_px = (left.cy_px + 0.5) * sy - 0.5;
  r.baseline_mm = baseline.norm();
  r.validate("rectified camera");
  return r;
}

}  // namespace touchcloud
