// The gel at rest as the rectified pair sees it: each view's disparity map
// and where the view sees the gel at all. GS-DepthNet predicts the
// disparity relative to it. The paper bounds its output to [0, d_max = 12 px]
// and its semantic loss (Eq. 6) pulls the disparity outside contact to 0, so
// its disparity is the gel's displacement from rest; our simulated rig sees
// the resting gel at 55-82 px, so the network's zero is this map instead.
// Measured without ground truth from one pair of the gel at rest (what a
// user records before touching anything) by a classical matcher. Torch-free.
#pragma once

#include <string>

#include <opencv2/core.hpp>

namespace touchcloud::learning {

struct ReferenceDisparity {
  // At the input size: CV_32FC1 px (left view's at left pixels, right
  // view's at right pixels; beyond the gel, the nearest gel pixel's value on
  // the row) and CV_8UC1 masks, 255 where the view sees the gel.
  cv::Mat left_px, right_px, gel_left, gel_right;

  // The view's map of input rows [row0, row0 + height) at a rows x cols
  // scale of that band (area average), px of the input.
  cv::Mat map(bool right_view, int row0, int height, int rows, int cols) const;
  // The view's gel mask of input rows [row0, row0 + height), 1 on the gel, 0 elsewhere (CV_32FC1).
  cv::Mat gel(bool right_view, int row0, int height) const;

  // Bytes for a checkpoint blob and back; InputError naming `where`.
  std::string bytes() const;
  static ReferenceDisparity parse(const std::string& bytes, const std::string& where);
};

// From a matcher's left and right disparities of the rest pair (CV_32FC1,
// CV_8UC1 masks of valid pixels): a 5 x 5 median of the valid values (the
// matcher's speckle), the gel as the valid pixels' row span, the span's
// holes and the rows beyond it filled from the nearest value on the row.
// InputError naming `where` when fewer than 10 % of the pixels are valid.
ReferenceDisparity reference_from_rest(const cv::Mat& left_px, const cv::Mat& valid_left, const cv::Mat& right_px,
                                       const cv::Mat& valid_right, const std::string& where);

}  // namespace touchcloud::learning
