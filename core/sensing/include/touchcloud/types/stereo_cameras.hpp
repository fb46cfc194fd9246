// The two cameras of a stereo rig as stereo calibration finds them:
// intrinsics with lens distortion, and the right camera's pose relative to
// the left (OpenCV axes, mm). The plate is not part of it.
#pragma once

#include <memory>

#include <Eigen/Geometry>

#include "touchcloud/data_type_name.hpp"
#include "touchcloud/optics/pinhole_camera.hpp"

namespace touchcloud {

struct StereoCameras {
  optics::CameraIntrinsics left, right;
  Eigen::Isometry3d right_from_left = Eigen::Isometry3d::Identity();  // maps left-camera points to the right camera
};
using StereoCamerasPtr = std::shared_ptr<const StereoCameras>;

}  // namespace touchcloud

TOUCHCLOUD_DATA_TYPE(touchcloud::StereoCamerasPtr, "stereo_cameras");
