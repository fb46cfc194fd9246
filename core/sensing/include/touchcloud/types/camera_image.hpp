// One camera's image: the frame of a single-camera sensor, or one camera of a
// stereo sensor read alone. Needs OpenCV: only plugins that handle images
// include this header (and link OpenCV themselves).
#pragma once

#include <memory>

#include <opencv2/core.hpp>

#include "touchcloud/data_type_name.hpp"
#include "touchcloud/types/camera_view.hpp"
#include "touchcloud/types/frames.hpp"

namespace touchcloud {

struct CameraImage {
  cv::Mat image;                       // 8-bit grey or BGR
  CameraView view = CameraView::Mono;  // the camera that took it
  double timestamp_s = 0;
  long index = 0;                      // frame number within the run
  SensorPose pose;                     // where the sensor was when the image was taken
};
using CameraImagePtr = std::shared_ptr<const CameraImage>;

}  // namespace touchcloud

TOUCHCLOUD_DATA_TYPE(touchcloud::CameraImagePtr, "camera_image");
