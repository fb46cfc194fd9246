// Draws marker dots into an 8-bit grey image as the GelStereo cameras see
// them: dark round dots on a bright, unevenly lit gel (smooth vignetting and
// a gentle side-to-side gradient). Each dot is anti-aliased analytically: a
// pixel on the rim is covered by the share of its square inside the rim
// (taken as straight across the pixel), so the dot's centroid sits at the
// sub-pixel centre given and its ink matches the disc's area. No OpenGL, no
// display.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

namespace touchcloud::simulation {

struct MarkerDot {
  Eigen::Vector2d centre_px;  // x right, y down; pixel (0, 0) is the top-left pixel's centre
  double radius_px = 0;
};

struct RenderStyle {
  double background_grey = 200.0;  // at the image centre
  double vignetting = 0.35;        // relative fall-off at the corners
  double gradient = 0.08;          // relative brightening from left to right edge
  double marker_grey = 40.0;       // a dot's core
};

class MarkerRenderer {
 public:
  // Precomputes the background once (rendering then copies it).
  MarkerRenderer(int width_px, int height_px, const RenderStyle& style);

  // An image of `dots` on the background (CV_8UC1). Overlapping dots take the darker value.
  cv::Mat render(const std::vector<MarkerDot>& dots) const;
  const cv::Mat& background() const { return background_; }

 private:
  cv::Mat background_;
  double marker_grey_;
};

}  // namespace touchcloud::simulation
