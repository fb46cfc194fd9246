// The gel's height map of a monocular GelSight-type sensor: how far the gel
// is pushed towards the camera at each pixel (mm, >= 0 where the gel is
// pressed), with a validity mask and a contact mask. As in dense_maps.hpp, an
// invalid pixel holds 0 and is marked in `valid` (255 valid, 0 not): never
// NaN. Pixel (u, v) lies at sensor_point(u, v) in the sensor frame (origin on
// the plate's gel-side face at the image centre, z into the gel; see
// sensor/gelsight_sensor.hpp). Needs OpenCV.
#pragma once

#include <memory>
#include <string>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "touchcloud/data_type_name.hpp"
#include "touchcloud/types/frames.hpp"

namespace touchcloud {

struct HeightMap {
  cv::Mat height_mm;         // CV_32FC1
  cv::Mat valid;             // CV_8UC1
  cv::Mat contact_mask;      // CV_8UC1, 255 where the gel touches the object; empty when not computed
  std::string sensor;        // the sensor's name
  double mm_per_px = 0;
  double gel_thickness_mm = 0;  // the gel's outer face at rest is z = gel_thickness_mm
  double timestamp_s = 0;
  long index = 0;
  SensorPose pose;           // where the sensor was

  // The gel surface at pixel (u, v) with height h, in the sensor frame (mm).
  Eigen::Vector3d sensor_point(double u, double v, double h_mm) const {
    return {(u - 0.5 * (height_mm.cols - 1)) * mm_per_px, (v - 0.5 * (height_mm.rows - 1)) * mm_per_px,
            gel_thickness_mm - h_mm};
  }
};
using HeightMapPtr = std::shared_ptr<const HeightMap>;

}  // namespace touchcloud

TOUCHCLOUD_DATA_TYPE(touchcloud::HeightMapPtr, "height_map");
