// Rays of a rectified pair's pixels through the plate, in the left camera
// frame (mm): what the colour-pattern renderer draws and what the refractive
// disparity-to-cloud conversion traces. The plate model is the rig's
// (refractive_projection.hpp); nothing of it is redone here.
#pragma once

#include <Eigen/Core>

#include "touchcloud/optics/stereo_rig.hpp"
#include "touchcloud/types/rectified_stereo.hpp"

namespace touchcloud::optics {

// Unit direction in the left camera frame of the ray through a rectified pixel.
Eigen::Vector3d rectified_direction(const RectifiedStereo& rect, StereoSide side, const Eigen::Vector2d& pixel_px);

// The rectified pixel of a direction in the left camera frame (OutOfView off the image, BehindCamera).
PixelProjection rectified_pixel(const RectifiedStereo& rect, StereoSide side, const Eigen::Vector3d& direction_left);

// A rectified pixel's ray refracted into the silicone (left frame).
SiliconeRay rectified_silicone_ray(const StereoRig& rig, const RectifiedStereo& rect, StereoSide side,
                                   const Eigen::Vector2d& pixel_px);

// Forward projection of a point in the silicone (left frame) into one rectified view.
PixelProjection project_rectified_refracted(const StereoRig& rig, const RectifiedStereo& rect, StereoSide side,
                                            const Eigen::Vector3d& point_left_mm);

}  // namespace touchcloud::optics
