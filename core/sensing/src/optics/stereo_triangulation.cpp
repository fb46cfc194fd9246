#include "touchcloud/optics/stereo_triangulation.hpp"

namespace touchcloud::optics {

namespace {

TriangulatedPoint invalid_pair(TraceStatus left, TraceStatus right) {
  TriangulatedPoint out;
  out.status = left != TraceStatus::Ok ? TriangulationStatus::LeftRayInvalid : TriangulationStatus::RightRayInvalid;
  out.left_ray = left;
  out.right_ray = right;
  return out;
}

}  // namespace

TriangulatedPoint triangulate_refractive(const StereoRig& rig, const Eigen::Vector2d& left_px,
                                         const Eigen::Vector2d& right_px, const RayTriangulationOptions& options) {
  const SiliconeRay left = back_project_refracted(rig, StereoSide::Left, left_px);
  const SiliconeRay right = back_project_refracted(rig, StereoSide::Right, right_px);
  if (left.status != TraceStatus::Ok || right.status != TraceStatus::Ok)
    return invalid_pair(left.status, right.status);
  return triangulate_rays(left.origin_mm, left.direction, right.origin_mm, right.direction, options);
}

TriangulatedPoint triangulate_pinhole(const StereoRig& rig, const Eigen::Vector2d& left_px,
                                      const Eigen::Vector2d& right_px, const RayTriangulationOptions& options) {
  const auto air_ray = [&](StereoSide side, const Eigen::Vector2d& pixel_px) {
    const PinholeCamera& camera = rig.camera(side);
    if (!camera.in_view(pixel_px)) return PixelDirection{TraceStatus::OutOfView, Eigen::Vector3d::Zero()};
    PixelDirection ray = camera.back_project(pixel_px);
    ray.direction = rig.camera_from_left(side).linear().transpose() * ray.direction;
    return ray;
  };
  const PixelDirection left = air_ray(StereoSide::Left, left_px);
  const PixelDirection right = air_ray(StereoSide::Right, right_px);
  if (left.status != TraceStatus::Ok || right.status != TraceStatus::Ok)
    return invalid_pair(left.status, right.status);
  return triangulate_rays(rig.centre_mm(StereoSide::Left), left.direction, rig.centre_mm(StereoSide::Right),
                          right.direction, options);
}

}  // namespace touchcloud::optics
