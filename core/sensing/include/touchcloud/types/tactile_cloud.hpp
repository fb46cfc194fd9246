// The marker cloud of one frame in the sensor frame, with the no-contact
// reference cloud and each marker's displacement from it.
#pragma once

#include <memory>
#include <vector>

#include "touchcloud/data_type_name.hpp"
#include "touchcloud/types/frames.hpp"
#include "touchcloud/types/point_cloud.hpp"

namespace touchcloud {

struct TactileCloud {
  CloudConstPtr points;                  // marker positions now, sensor frame, mm
  CloudConstPtr reference;               // the same markers without contact, same order
  std::vector<double> displacement_mm;   // |points[i] - reference[i]|
  std::vector<int> marker_ids;           // gel marker id of each point
  double timestamp_s = 0;
  SensorPose pose;                       // sensor pose when it was sensed
};
using TactileCloudPtr = std::shared_ptr<const TactileCloud>;

}  // namespace touchcloud

TOUCHCLOUD_DATA_TYPE(touchcloud::TactileCloudPtr, "tactile_cloud");
