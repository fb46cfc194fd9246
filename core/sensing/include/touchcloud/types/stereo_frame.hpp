// One stereo image pair from the sensor. Needs OpenCV: only plugins that
// handle images include this header (and link OpenCV themselves).
#pragma once

#include <memory>

#include <opencv2/core.hpp>

#include "touchcloud/data_type_name.hpp"
#include "touchcloud/types/frames.hpp"

namespace touchcloud {

struct StereoFrame {
  cv::Mat left, right;  // same size and type; 8-bit grey or BGR
  double timestamp_s = 0;
  long index = 0;       // frame number within the run
  SensorPose pose;      // where the sensor was when the frame was taken
};
using StereoFramePtr = std::shared_ptr<const StereoFrame>;

}  // namespace touchcloud

TOUCHCLOUD_DATA_TYPE(touchcloud::StereoFramePtr, "stereo_frame");
