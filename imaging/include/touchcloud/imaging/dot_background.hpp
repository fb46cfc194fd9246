// The gel's lighting without the dots, and which pixels differ from it enough
// to be part of a dot.
//
// The lighting (vignetting, gradients) changes over tens of pixels, the dots
// over a few, so the background is estimated on a copy shrunk 2-4x (linear
// interpolation): a closing (dark dots) or opening (bright dots) with a window
// wider than the largest dot removes them, and a box blur of the same width
// smooths the result. Each full-resolution pixel is compared with the
// background of its block: within a block the lighting changes by well under
// a grey level, and no full-size background image is ever made.
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "touchcloud/imaging/mask_blobs.hpp"

namespace touchcloud::imaging {

class DotBackground {
 public:
  // `window_px`: the closing/opening window at full resolution.
  DotBackground(bool dark_dots, int window_px);

  void estimate(const cv::Mat& grey);  // CV_8UC1
  int scale() const { return scale_; }

  // The pixels of row y of `grey` (the image estimate() saw) whose contrast
  // with the background exceeds `threshold_grey`: background - grey for dark
  // dots, grey - background for bright ones.
  void mask_row(const cv::Mat& grey, int y, int threshold_grey, MaskBlobs::RowBits& bits);

 private:
  bool dark_;
  int scale_;
  cv::Mat kernel_;
  cv::Mat small_, small_background_;
  std::vector<std::uint8_t> limit_row_;  // per pixel: the grey level a dot pixel must pass
  int limit_row_of_ = -1;                // the shrunk row it was made from
  int limit_threshold_ = -1;
};

}  // namespace touchcloud::imaging
