// Named coordinate frames. Transforms are written target_from_source, so
// `base_from_sensor * p_sensor` is p in the base frame.
#pragma once

#include <Eigen/Geometry>

#include "touchcloud/data_type_name.hpp"

namespace touchcloud {

enum class Frame { Camera, Sensor, Base };

// Pose of the sensor in the robot base frame {B}; translation in mm.
struct SensorPose {
  Eigen::Isometry3d base_from_sensor = Eigen::Isometry3d::Identity();
};

}  // namespace touchcloud

TOUCHCLOUD_DATA_TYPE(touchcloud::SensorPose, "pose");
