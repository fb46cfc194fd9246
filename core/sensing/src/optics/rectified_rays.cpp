#include "touchcloud/optics/rectified_rays.hpp"

namespace touchcloud::optics {

namespace {

// Rotation from the left camera frame into either rectified view's frame:
// the two rectified frames are parallel.
const Eigen::Matrix3d& rect_from_left(const RectifiedStereo& rect, StereoSide) { return rect.left_rect_from_left; }

double cx(const RectifiedStereo& rect, StereoSide side) {
  return side == StereoSide::Left ? rect.cx_left_px : rect.cx_right_px;
}

}  // namespace

Eigen::Vector3d rectified_direction(const RectifiedStereo& rect, StereoSide side, const Eigen::Vector2d& pixel_px) {
  const Eigen::Vector3d in_rect((pixel_px.x() - cx(rect, side)) / rect.fx_px, (pixel_px.y() - rect.cy_px) / rect.fy_px,
                                1.0);
  return (rect_from_left(rect, side).transpose() * in_rect).normalized();
}

PixelProjection rectified_pixel(const RectifiedStereo& rect, StereoSide side, const Eigen::Vector3d& direction_left) {
  const Eigen::Vector3d d = rect_from_left(rect, side) * direction_left;
  if (!(d.z() > 0)) return {TraceStatus::BehindCamera, Eigen::Vector2d::Zero()};
  const Eigen::Vector2d px(cx(rect, side) + rect.fx_px * d.x() / d.z(), rect.cy_px + rect.fy_px * d.y() / d.z());
  const bool in_view = px.x() >= -0.5 && px.x() < rect.width_px - 0.5 && px.y() >= -0.5 && px.y() < rect.height_px - 0.5;
  return {in_view ? TraceStatus::Ok : TraceStatus::OutOfView, px};
}

SiliconeRay rectified_silicone_ray(const StereoRig& rig, const RectifiedStereo& rect, StereoSide side,
                                   const Eigen::Vector2d& pixel_px) {
  return trace_into_silicone(rig.plate(), rig.centre_mm(side), rectified_direction(rect, side, pixel_px));
}

PixelProjection project_rectified_refracted(const StereoRig& rig, const RectifiedStereo& rect, StereoSide side,
                                            const Eigen::Vector3d& point_left_mm) {
  const AirDirection air = air_direction_to(rig.plate(), rig.centre_mm(side), point_left_mm);
  if (air.status != TraceStatus::Ok) return {air.status, Eigen::Vector2d::Zero()};
  return rectified_pixel(rect, side, air.direction);
}

}  // namespace touchcloud::optics
