// The image of a GelSight-type sensor from the gel's height map: shading of
// the surface normals under the sensor's coloured lights (the smooth model of
// sensor/gelsight_sensor.hpp) over the no-contact background. A flat gel
// renders the background exactly.
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "touchcloud/sensor/gelsight_sensor.hpp"

namespace touchcloud::simulation {

class PhotometricRenderer {
 public:
  explicit PhotometricRenderer(const sensor::GelSightSensor& sensor);

  // The gel without contact: CV_8UC3 BGR.
  const cv::Mat& background() const { return background_; }
  // CV_8UC3 BGR of a CV_32FC1 height map (mm) of the sensor's image size.
  cv::Mat render(const cv::Mat& height_mm) const;

  // What the lights give a surface of unit normal `n` (R, G, B grey levels).
  Eigen::Vector3d shading(const Eigen::Vector3d& n) const;
  // The normal of the surface H with gradient (gx, gy) (see the sensor's frame).
  static Eigen::Vector3d normal(double gx, double gy) { return Eigen::Vector3d(-gx, -gy, 1.0).normalized(); }

 private:
  sensor::GelSightSensor sensor_;
  cv::Mat background_f_;   // CV_32FC3 BGR, unrounded
  cv::Mat background_;     // CV_8UC3
  Eigen::Vector3d flat_;   // shading of the flat gel
};

}  // namespace touchcloud::simulation
