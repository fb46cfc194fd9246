// Per-pixel maps of a rectified stereo pair (the colour-pattern GelStereo):
// disparities, depth, contact mask, with the rectified camera they belong to.
// A map that was not computed is empty. Invalid pixels are marked in the
// map's validity mask (255 valid, 0 not) and hold 0 in the map: never NaN,
// never a guess. Needs OpenCV: only plugins that handle images include this
// header (and link OpenCV themselves).
#pragma once

#include <memory>

#include <opencv2/core.hpp>

#include "touchcloud/data_type_name.hpp"
#include "touchcloud/types/frames.hpp"
#include "touchcloud/types/rectified_stereo.hpp"

namespace touchcloud {

struct DenseMaps {
  // CV_32FC1, px. Left: a left pixel x matches the right pixel x - d. Right:
  // a right pixel x matches the left pixel x + d. Both >= 0 where valid.
  cv::Mat disparity_left_px, disparity_right_px;
  cv::Mat valid_left, valid_right;  // CV_8UC1 masks of the two disparity maps
  cv::Mat depth_mm;                 // CV_32FC1: z of the gel surface in the rectified left camera frame
  cv::Mat depth_valid;              // CV_8UC1
  cv::Mat contact_mask;             // CV_8UC1, left view: 255 where the gel touches the object
  RectifiedStereo camera;           // the pair the maps are of (size = every map's size)
  double timestamp_s = 0;
  long index = 0;                   // frame number within the run
  SensorPose pose;                  // where the sensor was
};
using DenseMapsPtr = std::shared_ptr<const DenseMaps>;

}  // namespace touchcloud

TOUCHCLOUD_DATA_TYPE(touchcloud::DenseMapsPtr, "dense_maps");
