// One rectified colour stereo pair (the colour-pattern GelStereo), with the
// rectified camera it was taken or rendered with. Grey marker frames stay
// StereoFrame. Needs OpenCV: only plugins that handle images include this
// header (and link OpenCV themselves).
#pragma once

#include <memory>

#include <opencv2/core.hpp>

#include "touchcloud/data_type_name.hpp"
#include "touchcloud/types/frames.hpp"
#include "touchcloud/types/rectified_stereo.hpp"

namespace touchcloud {

struct ColourStereoFrame {
  cv::Mat left, right;      // CV_8UC3 BGR, rectified, camera.width_px x camera.height_px
  RectifiedStereo camera;
  double timestamp_s = 0;
  long index = 0;           // frame number within the run
  SensorPose pose;          // where the sensor was when the pair was taken
};
using ColourStereoFramePtr = std::shared_ptr<const ColourStereoFrame>;

}  // namespace touchcloud

TOUCHCLOUD_DATA_TYPE(touchcloud::ColourStereoFramePtr, "colour_stereo_frame");
