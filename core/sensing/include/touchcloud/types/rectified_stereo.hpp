// The rectified camera pair that dense stereo works in: both views share the
// focal lengths and cy, rows are epipolar lines, and a left pixel x sees the
// point the right view sees at x - d (d >= 0, the left disparity in px).
// Points are in mm. Eigen only: the runtime-free types may include it.
#pragma once

#include <Eigen/Geometry>

#include "touchcloud/optics/stereo_rig.hpp"

namespace touchcloud {

struct RectifiedStereo {
  int width_px = 0, height_px = 0;
  double fx_px = 0, fy_px = 0;      // shared by both views
  double cx_left_px = 0, cx_right_px = 0, cy_px = 0;
  double baseline_mm = 0;           // right centre along the rectified x axis of the left
  // Rotations from each (unrectified) camera frame into its rectified frame
  // (OpenCV's R1, R2); both rectified frames are parallel.
  Eigen::Matrix3d left_rect_from_left = Eigen::Matrix3d::Identity();
  Eigen::Matrix3d right_rect_from_right = Eigen::Matrix3d::Identity();

  // Eq. 8-9's Q: Q * [x, y, d, 1] is the point in the rectified left frame,
  // homogeneous (divide by the last entry). Exact for fx != fy too.
  Eigen::Matrix4d q() const;
  // Throws InputError naming `what`'s field that is wrong.
  void validate(const char* what = "rectified camera") const;
};

// Rectification of a rig's two cameras (lens distortion ignored: simulated
// pairs are rendered rectified): the left camera's axes turned so that x runs
// along the baseline; focal lengths and principal point of the left camera,
// scaled to `width_px` x `height_px` (0: the left camera's size).
RectifiedStereo rectify_stereo_rig(const optics::StereoRig& rig, int width_px = 0, int height_px = 0);

}  // namespace touchcloud
