// Disparity to 3D (the GS-DepthNet paper, Section III-E): the left disparity averaged with
// the right view's (Eq. 7), then each pixel to a point, either by the Q
// matrix of the rectified pair (Eq. 8-9: straight rays, as the paper does) or
// by tracing the pixel's two rays through the plate and intersecting them in
// the silicone (RSRT, touchcloud/optics; the paper does not): the left
// pixel's ray and the right ray of column x - d at the row where the right
// view sees that point (through the plate, rows are not exactly epipolar).
// Points in the sensor frame, mm, in double precision.
#pragma once

#include <optional>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "touchcloud/optics/ray_triangulation.hpp"
#include "touchcloud/optics/stereo_rig.hpp"
#include "touchcloud/types/dense_maps.hpp"

namespace touchcloud::disparity_to_cloud {

enum class DisparitySource {
  Average,  // Eq. 7: (d_l(x) + d_r(x - d_l(x))) / 2, d_r interpolated linearly
  Left,     // the left map alone
};

struct ConversionCounts {
  long pixels = 0;          // valid left disparities looked at
  long no_right = 0;        // Eq. 7 found no valid right disparity at x - d
  long not_triangulated = 0;  // Q: at or behind infinity; refraction: a ray failed or the rays were degenerate
};

class DisparityConversion {
 public:
  // `rig`: the sensor's cameras and plate (left camera frame); the maps'
  // rectified camera must be a rectification of the rig (rectify_stereo_rig,
  // or stereo_rectification's stereoRectify): InputError naming `where` otherwise.
  DisparityConversion(const optics::StereoRig& rig, const Eigen::Isometry3d& sensor_from_left, bool refraction);

  // The disparity Eq. 7 gives at left pixel (x, y), or nothing when the
  // left or (Average) the right map is invalid there.
  std::optional<double> disparity_px(const DenseMaps& maps, int x, int y, DisparitySource source) const;

  // The point of left pixel (x, y) with disparity d, sensor frame (mm), or
  // nothing when it cannot be triangulated.
  std::optional<Eigen::Vector3d> point_mm(const RectifiedStereo& rect, double x, double y, double d) const;

  // Checks that the maps' camera rectifies this rig: parallel rectified
  // frames, x along the baseline, the rig's baseline.
  void require_same_camera(const RectifiedStereo& rect, const std::string& where) const;

 private:
  optics::StereoRig rig_;
  Eigen::Isometry3d sensor_from_left_;
  bool refraction_;
};

}  // namespace touchcloud::disparity_to_cloud
