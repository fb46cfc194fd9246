#include "touchcloud/optics/stereo_rig.hpp"

#include <cmath>
#include <utility>

#include "config_check.hpp"

namespace touchcloud::optics {

const char* to_string(StereoSide side) { return side == StereoSide::Left ? "left" : "right"; }

StereoRig::StereoRig(PinholeCamera left, PinholeCamera right, const Eigen::Isometry3d& right_from_left,
                     const RefractivePlate& plate_left)
    : left_(std::move(left)), right_(std::move(right)), right_from_left_(right_from_left), plate_(plate_left) {
  plate_.validate("stereo_rig.plate");
  ConfigCheck check("stereo_rig");
  const Eigen::Matrix3d rotation = right_from_left_.linear();
  const double orthonormality = (rotation.transpose() * rotation - Eigen::Matrix3d::Identity()).norm();
  check.require(rotation.allFinite() && orthonormality <= 1e-9 && rotation.determinant() > 0,
                "right_from_left.rotation", "off orthonormal by " + format_number(orthonormality),
                "a rotation (orthonormal within 1e-9, determinant +1)");
  check.require(right_from_left_.translation().allFinite(), "right_from_left.translation", "non-finite",
                "finite");
  check.throw_if_failed();
  // Only meaningful once the pose is known to be a rotation.
  const double right_air_mm = plate_.distance_mm - plate_.normal.dot(centre_mm(StereoSide::Right));
  check.require(right_air_mm > 0, "right camera centre's distance to the plate", right_air_mm,
                "> 0 (the right camera must be on the air side of the plate)");
  check.throw_if_failed();
}

const PinholeCamera& StereoRig::camera(StereoSide side) const {
  return side == StereoSide::Left ? left_ : right_;
}

Eigen::Vector3d StereoRig::centre_mm(StereoSide side) const {
  return side == StereoSide::Left ? Eigen::Vector3d::Zero() : Eigen::Vector3d(right_from_left_.inverse().translation());
}

Eigen::Isometry3d StereoRig::camera_from_left(StereoSide side) const {
  return side == StereoSide::Left ? Eigen::Isometry3d::Identity() : right_from_left_;
}

StereoRig StereoRig::swapped() const {
  return StereoRig(right_, left_, right_from_left_.inverse(), plate_.expressed_in(right_from_left_));
}

RefractedPixel project_refracted(const StereoRig& rig, StereoSide side, const Eigen::Vector3d& point_left_mm) {
  const AirDirection air = air_direction_to(rig.plate(), rig.centre_mm(side), point_left_mm);
  if (air.status != TraceStatus::Ok) return {air.status, Eigen::Vector2d::Zero()};
  const Eigen::Vector3d direction_camera = rig.camera_from_left(side).linear() * air.direction;
  const PixelProjection pixel = rig.camera(side).project(direction_camera);
  // A refracted path that leaves the camera backwards cannot be imaged at all.
  const TraceStatus status = pixel.status == TraceStatus::BehindCamera ? TraceStatus::OutOfView : pixel.status;
  return {status, pixel.pixel_px};
}

SiliconeRay back_project_refracted(const StereoRig& rig, StereoSide side, const Eigen::Vector2d& pixel_px) {
  const PinholeCamera& camera = rig.camera(side);
  if (!camera.in_view(pixel_px)) return {TraceStatus::OutOfView, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  const PixelDirection ray = camera.back_project(pixel_px);
  if (ray.status != TraceStatus::Ok) return {ray.status, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  const Eigen::Vector3d direction_left = rig.camera_from_left(side).linear().transpose() * ray.direction;
  return trace_into_silicone(rig.plate(), rig.centre_mm(side), direction_left);
}

}  // namespace touchcloud::optics
