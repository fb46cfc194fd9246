// Marker dots printed on a GelSight-type gel (the scene effect `markers`):
// a square grid of dark dots centred on the image, each dot drawn over the
// rendered shading by scaling the pixel by 1 - darkness x coverage (the
// share of the pixel the disc covers, 4 x 4 samples per pixel).
//
// The dots move with the gel. The approximation: a pressed gel pushes its
// surface sideways, away from where it is pressed highest, by an amount
// that grows with the slope; a dot at rest at p moves to
//
//     p - shift_per_slope_mm x grad H(p)      (mm; H the pad's height in mm)
//
// so a flat press moves nothing, and the dots around a ball's cap move
// outwards, most on its steep rim. It is no elastic model (no shear from
// sliding, no spread beyond the slope), but it gives a displacement field
// with a known truth for marker tracking. Dots are kept when the whole dot
// is inside the image at rest.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "touchcloud/sensor/gelsight_sensor.hpp"

namespace touchcloud::simulation {

struct GelMarkerOptions {
  double pitch_mm = 2.0;            // grid spacing, rows and columns
  double diameter_mm = 0.5;         // a dot's diameter on the gel
  double darkness = 0.7;            // share of the light a dot's centre takes away, in (0, 1]
  double shift_per_slope_mm = 0.5;  // lateral motion per unit slope of the pressed surface
};

class GelMarkers {
 public:
  GelMarkers(const sensor::GelSightSensor& sensor, GelMarkerOptions options);

  const GelMarkerOptions& options() const { return options_; }
  double diameter_px() const { return diameter_px_; }
  // The dots' centres at rest (px; (0, 0) the top-left pixel's centre), row by row.
  const std::vector<cv::Point2d>& rest_px() const { return rest_px_; }
  // The centres on the pressed gel of height `height_mm` (CV_32FC1, the image's size).
  std::vector<cv::Point2d> moved_px(const cv::Mat& height_mm) const;
  // Darkens the dots centred at `centres_px` into `bgr` (CV_8UC3).
  void draw(cv::Mat& bgr, const std::vector<cv::Point2d>& centres_px) const;

 private:
  GelMarkerOptions options_;
  double mm_per_px_;
  double diameter_px_;
  std::vector<cv::Point2d> rest_px_;
};

}  // namespace touchcloud::simulation
