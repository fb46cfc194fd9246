// Measuring one blob (a dot, or a clump of dots that touch or overlap in the
// image) over a window of the grey image around it: contrast-weighted centre
// and second moments, and the split of a clump into its dots.
//
// The window's rim (its sides inside the image) gives the local background,
// and a pixel's contrast is its difference from it towards the dots' side, so
// lighting that changes across the image does not pull centres towards the
// window's middle. Pixels weigh by their contrast above a floor: the
// background's noise then weighs nothing, and a dot's weights, a monotone
// function of its round profile, stay centred on it. Pixels of other blobs
// (past the threshold outside the blob's bounding box) are left out.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

namespace touchcloud::imaging {

struct DotMoments {
  double ink = 0;        // weight: contrast above the floor, summed (grey levels x px)
  double peak_grey = 0;  // largest contrast
  Eigen::Vector2d centre_px = Eigen::Vector2d::Zero();
  Eigen::Matrix2d covariance_px2 = Eigen::Matrix2d::Zero();  // contrast-weighted, about the centre
  bool clipped = false;  // the window crosses the image border

  // Principal variances (largest first) and the direction of the largest.
  Eigen::Vector2d principal_variances_px2() const;
  Eigen::Vector2d major_axis() const;
  // Ratio of the principal axes: 1 for a round dot, about 2 for two touching ones.
  double elongation() const;
  // How many round dots of the blob's width its ink amounts to: about 1 for a
  // dot, 1.6-2 for two merged ones. A dot of radius r has minor variance
  // r^2 / 4 (plus the blur's), hence ink / (4 pi minor_variance peak).
  double dots_by_ink() const;
};

// A window of the image, and which of its sides the image border cut off.
struct DotWindow {
  cv::Rect rect;
  bool cut_left = false, cut_right = false, cut_top = false, cut_bottom = false;
  bool clipped() const { return cut_left || cut_right || cut_top || cut_bottom; }
};
// `wanted` cut to the image.
DotWindow fit_window(const cv::Rect& wanted, cv::Size image);

struct ContrastLevels {
  int threshold_grey = 0;        // a blob's pixels have more contrast than this
  double weight_floor_grey = 0;  // weights are the contrast above this
};

// `grey` is CV_8UC1; `dark`: the dots are darker than the background;
// `blob_box` is the blob's bounding box.
DotMoments measure_dot(const cv::Mat& grey, bool dark, const DotWindow& window, const cv::Rect& blob_box,
                       const ContrastLevels& levels);

// Splits a clump measured as `whole` over `window` into `dots` dots: weighted
// k-means of the window's pixels, seeded evenly along the clump's long axis.
std::vector<DotMoments> split_clump(const cv::Mat& grey, bool dark, const DotWindow& window,
                                    const cv::Rect& blob_box, const ContrastLevels& levels, const DotMoments& whole,
                                    int dots);

}  // namespace touchcloud::imaging
