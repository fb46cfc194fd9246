// One colour image of a monocular GelSight-type sensor (the ContactNet/TactileDepthNet report's): the gel
// seen from behind under its coloured LEDs. Needs OpenCV: only plugins that
// handle images include this header (and link OpenCV themselves).
#pragma once

#include <memory>
#include <string>

#include <opencv2/core.hpp>

#include "touchcloud/data_type_name.hpp"
#include "touchcloud/types/frames.hpp"

namespace touchcloud {

struct MonoColourFrame {
  cv::Mat image;            // CV_8UC3 BGR, the sensor's image size
  std::string sensor;       // the sensor's name (sensor.name): calibrations belong to one sensor
  double mm_per_px = 0;     // pixel pitch on the gel (see sensor/gelsight_sensor.hpp for the frame)
  double timestamp_s = 0;
  long index = 0;           // frame number within the run
  SensorPose pose;          // where the sensor was when the image was taken
};
using MonoColourFramePtr = std::shared_ptr<const MonoColourFrame>;

}  // namespace touchcloud

TOUCHCLOUD_DATA_TYPE(touchcloud::MonoColourFramePtr, "mono_colour_frame");
