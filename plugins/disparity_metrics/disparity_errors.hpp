// The disparity error metrics of the colour-pattern GelStereo paper's
// Table I (after Eigen et al.): Abs Rel, Sq Rel, RMSE, RMSE log and the
// share of pixels with max(d/d*, d*/d) below 1.25, 1.25^2, 1.25^3, pooled
// over every pixel of every pair where the truth is valid (and, for the
// contact region, in contact).
//
// An estimate marked invalid (or not positive) at such a pixel is not
// guessed: it leaves the error sums out, counts against coverage, and
// fails every threshold. So a matcher that leaves holes scores lower in
// the thresholds, as a dense method is judged on every pixel.
#pragma once

#include <array>

#include <opencv2/core.hpp>

namespace touchcloud::disparity_metrics {

class DisparityErrors {
 public:
  // Adds the pixels of one pair: `estimate`, `truth` CV_32FC1 px; their
  // validity masks and `region` CV_8UC1 (255 in); all the same size.
  // An empty `region` means every pixel.
  void add(const cv::Mat& estimate, const cv::Mat& estimate_valid, const cv::Mat& truth, const cv::Mat& truth_valid,
           const cv::Mat& region);

  long pixels() const { return pixels_; }    // truth valid, in the region
  long matched() const { return matched_; }  // of those, with a valid estimate
  double coverage() const { return pixels_ ? static_cast<double>(matched_) / pixels_ : 0.0; }

  // Over the matched pixels (0 when none).
  double abs_rel() const { return mean(abs_rel_); }
  double sq_rel() const { return mean(sq_rel_); }
  double rmse_px() const;
  double rmse_log() const;
  // Over all pixels: k = 1, 2, 3.
  double delta_below(int k) const;

 private:
  double mean(double sum) const { return matched_ ? sum / matched_ : 0.0; }

  long pixels_ = 0, matched_ = 0;
  double abs_rel_ = 0, sq_rel_ = 0, sq_ = 0, sq_log_ = 0;
  std::array<long, 3> below_{};
};

}  // namespace touchcloud::disparity_metrics
