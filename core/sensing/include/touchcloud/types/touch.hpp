// Where the robot touches next, in the robot base frame.
#pragma once

#include <Eigen/Core>

#include "touchcloud/data_type_name.hpp"

namespace touchcloud {

struct TouchTarget {
  Eigen::Vector2d xy_mm = Eigen::Vector2d::Zero();  // base frame; the touch descends along -z
  int grid_index = -1;                              // cell of the sampling grid, -1 when off-grid
  bool exploratory = false;                         // chosen by the model (true) or at random (false)
};

}  // namespace touchcloud

TOUCHCLOUD_DATA_TYPE(touchcloud::TouchTarget, "touch_target");
