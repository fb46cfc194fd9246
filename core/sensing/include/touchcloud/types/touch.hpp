// Where the robot touches next, in the robot base frame.
#pragma once

#include <optional>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "touchcloud/data_type_name.hpp"

namespace touchcloud {

struct TouchTarget {
  // In the approach frame: the base frame when the touch comes from above.
  // The touch descends along the approach frame's -z onto (x, y).
  Eigen::Vector2d xy_mm = Eigen::Vector2d::Zero();
  int grid_index = -1;                              // cell of the sampling grid, -1 when off-grid
  bool exploratory = false;                         // chosen by the model (true) or at random (false)
  // A touch from any side: the approach frame in the base frame (the palm's
  // normal is its -z, its roll about that axis the palm's). Not set: straight
  // down, the approach frame is the base frame.
  std::optional<Eigen::Isometry3d> base_from_approach;
};

}  // namespace touchcloud

TOUCHCLOUD_DATA_TYPE(touchcloud::TouchTarget, "touch_target");
