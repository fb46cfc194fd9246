// Classical stereo matching of a rectified colour pair (the GS-DepthNet paper's baselines):
// OpenCV's StereoBM (block matching, on grey) or StereoSGBM (semi-global,
// on colour), for the left view and, by matching the mirrored pair, for the
// right view; then a left-right consistency check. Pixels OpenCV leaves
// unmatched or the check rejects are marked invalid (0 in the mask, 0 in the
// map), never filled in.
#pragma once

#include <string>

#include <opencv2/core.hpp>

namespace touchcloud::imaging {

enum class MatchMethod { BlockMatching, SemiGlobal };
// OpenCV's StereoSGBM modes: five directions (MODE_SGBM), three (MODE_SGBM_3WAY,
// faster) or four (MODE_HH4).
enum class SgbmMode { FivePaths, ThreeWay, FourPaths };

struct MatcherOptions {
  MatchMethod method = MatchMethod::SemiGlobal;
  int block_size_px = 7;
  int min_disparity_px = 0;
  int num_disparities = 64;      // searched disparities: min_disparity_px .. + num_disparities - 1
  int uniqueness_ratio = 10;     // percent margin by which the best cost must win
  bool lr_check = true;
  double max_lr_difference_px = 1.0;
  SgbmMode sgbm_mode = SgbmMode::FivePaths;
  // The right view's disparities from a second pass on the mirrored pair
  // (the left-right check against them; Eq. 7 averages them). Without it,
  // one pass: the check is OpenCV's own within it (disp12MaxDiff,
  // max_lr_difference_px rounded up) and the right map is all invalid.
  bool right_pass = true;
  // OpenCV leaves the first min_disparity_px + num_disparities columns of the
  // reference view unmatched (their whole search range would have to lie in
  // the image). With full_width, both images are padded on that side by as
  // many black columns, so a column is matched whenever its match is in the
  // other image: a gel near the image's edge is matched too.
  bool full_width = false;

  // Throws ParameterError naming the parameter (block_size_px, num_disparities,
  // ...) whose value OpenCV's matcher would refuse, and why.
  void validate() const;
};

struct DisparityPair {
  cv::Mat left_px, right_px;        // CV_32FC1, 0 where invalid
  cv::Mat valid_left, valid_right;  // CV_8UC1, 255 valid
};

class DisparityMatcher {
 public:
  explicit DisparityMatcher(const MatcherOptions& options);  // validates
  const MatcherOptions& options() const { return options_; }

  // `left`, `right`: rectified, same size and type, CV_8UC3 (BGR) or CV_8UC1.
  // InputError naming `where` when they are not, or too small for the block
  // and the disparity range.
  DisparityPair match(const cv::Mat& left, const cv::Mat& right, const std::string& where) const;
  // Only the pixels of `region` of the left view (its rows, and its columns
  // with their search range beside them), the rest invalid: a contact's
  // disparities at a fraction of the whole pair's cost. One pass (the right
  // map all invalid); InputError naming `where` as match() and when the
  // options ask for the right pass.
  DisparityPair match_region(const cv::Mat& left, const cv::Mat& right, cv::Rect region,
                             const std::string& where) const;

 private:
  cv::Mat raw_disparity(const cv::Mat& left, const cv::Mat& right) const;  // CV_16S, 4 fractional bits
  int within_pass_check() const;
  void check_pair(const cv::Mat& left, const cv::Mat& right, const std::string& where) const;

  MatcherOptions options_;
};

// Left-right consistency: a left disparity d at x survives when the right
// disparity at round(x - d) is valid and within `max_difference_px` of it;
// likewise for the right map (at round(x + d)). Works on both maps in place.
void check_left_right(DisparityPair& pair, double max_difference_px);

}  // namespace touchcloud::imaging
