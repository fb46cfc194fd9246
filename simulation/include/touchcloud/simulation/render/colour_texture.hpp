// The colour-pattern GelStereo's printed layer (the GS-DepthNet paper, Section II): a
// seeded random, dense colour pattern, semitransparent over the white gel.
// Random colours on a grid of `feature_mm` cells, smoothed by a Gaussian of
// a third of a cell so that the pattern is band-limited (sampling it at any
// sub-pixel position is then well defined), blended with the gel's white.
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "touchcloud/sensor/gelstereo_sensor.hpp"

namespace touchcloud::simulation {

class ColourTexture {
 public:
  // Covers the gel's base disc of `radius_mm` (sensor frame x, y).
  ColourTexture(const sensor::ColourPatternSpec& spec, double radius_mm);

  const cv::Mat& image() const { return image_; }  // CV_8UC3 BGR
  // Texel coordinates (x right, y down, (0, 0) the first texel's centre) of
  // the sensor-frame point (x, y) on the gel.
  Eigen::Vector2f texel(double x_mm, double y_mm) const {
    return {static_cast<float>((x_mm - origin_mm_) / texel_mm_), static_cast<float>((y_mm - origin_mm_) / texel_mm_)};
  }

 private:
  cv::Mat image_;
  double origin_mm_, texel_mm_;
};

}  // namespace touchcloud::simulation
