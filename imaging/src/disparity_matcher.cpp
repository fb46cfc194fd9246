#include "touchcloud/imaging/disparity_matcher.hpp"

#include <cmath>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "touchcloud/error.hpp"

namespace touchcloud::imaging {

namespace {

// OpenCV's StereoBM limits (calib3d/src/stereobm.cpp) and StereoSGBM's.
constexpr int kBmMinBlock = 5, kBmMaxBlock = 255, kSgbmMaxBlock = 255;

std::string size_text(const cv::Mat& m) { return std::to_string(m.cols) + " x " + std::to_string(m.rows); }

std::string type_text(const cv::Mat& m) { return cv::typeToString(m.type()); }

// OpenCV's 16-bit fixed point (4 fractional bits) to px, with its mask.
void to_px(const cv::Mat& raw, int min_disparity, cv::Mat& px, cv::Mat& valid) {
  valid = raw >= min_disparity * 16;  // unmatched pixels hold (min_disparity - 1) * 16
  raw.convertTo(px, CV_32F, 1.0 / 16);
  px.setTo(0, ~valid);
}

}  // namespace

void MatcherOptions::validate() const {
  const bool bm = method == MatchMethod::BlockMatching;
  if (block_size_px % 2 == 0)
    throw ParameterError("block_size_px", std::to_string(block_size_px) + " is even; OpenCV's " +
                                              (bm ? "StereoBM" : "StereoSGBM") + " needs an odd block size");
  if (bm && (block_size_px < kBmMinBlock || block_size_px > kBmMaxBlock))
    throw ParameterError("block_size_px", std::to_string(block_size_px) + " is outside OpenCV StereoBM's [" +
                                              std::to_string(kBmMinBlock) + ", " + std::to_string(kBmMaxBlock) + "]");
  if (!bm && (block_size_px < 1 || block_size_px > kSgbmMaxBlock))
    throw ParameterError("block_size_px", std::to_string(block_size_px) + " is outside [1, " +
                                              std::to_string(kSgbmMaxBlock) + "] for StereoSGBM");
  if (num_disparities <= 0 || num_disparities % 16 != 0)
    throw ParameterError("num_disparities",
                         std::to_string(num_disparities) + " is not a positive multiple of 16, as OpenCV's matchers need");
  if (min_disparity_px < 0)
    throw ParameterError("min_disparity_px", std::to_string(min_disparity_px) +
                                                 " is negative: the gel is in front of both cameras, disparities are > 0");
  if (uniqueness_ratio < 0 || uniqueness_ratio > 100)
    throw ParameterError("uniqueness_ratio", std::to_string(uniqueness_ratio) + " is outside [0, 100] (percent)");
  if (!(max_lr_difference_px >= 0) || !std::isfinite(max_lr_difference_px))
    throw ParameterError("max_lr_difference_px", "must be a finite number >= 0");
}

DisparityMatcher::DisparityMatcher(const MatcherOptions& options) : options_(options) { options_.validate(); }

// OpenCV's disp12MaxDiff: -1 (off) where our own check runs on both views.
int DisparityMatcher::within_pass_check() const {
  return options_.lr_check && !options_.right_pass ? static_cast<int>(std::ceil(options_.max_lr_difference_px)) : -1;
}

cv::Mat DisparityMatcher::raw_disparity(const cv::Mat& left_in, const cv::Mat& right_in) const {
  const MatcherOptions& o = options_;
  const int pad = o.full_width ? o.min_disparity_px + o.num_disparities : 0;
  cv::Mat left = left_in, right = right_in, raw;
  if (pad > 0) {
    cv::copyMakeBorder(left_in, left, 0, 0, pad, 0, cv::BORDER_CONSTANT, cv::Scalar::all(0));
    cv::copyMakeBorder(right_in, right, 0, 0, pad, 0, cv::BORDER_CONSTANT, cv::Scalar::all(0));
  }
  if (o.method == MatchMethod::BlockMatching) {
    cv::Mat left_grey = left, right_grey = right;
    if (left.channels() == 3) {
      cv::cvtColor(left, left_grey, cv::COLOR_BGR2GRAY);
      cv::cvtColor(right, right_grey, cv::COLOR_BGR2GRAY);
    }
    auto bm = cv::StereoBM::create(o.num_disparities, o.block_size_px);
    bm->setMinDisparity(o.min_disparity_px);
    bm->setUniquenessRatio(o.uniqueness_ratio);
    bm->setDisp12MaxDiff(within_pass_check());
    bm->setSpeckleWindowSize(0);
    bm->compute(left_grey, right_grey, raw);
  } else {
    const int channels = left.channels(), area = o.block_size_px * o.block_size_px;
    // OpenCV's recommended smoothness penalties for this block and colour count.
    const int mode = o.sgbm_mode == SgbmMode::ThreeWay    ? cv::StereoSGBM::MODE_SGBM_3WAY
                     : o.sgbm_mode == SgbmMode::FourPaths ? cv::StereoSGBM::MODE_HH4
                                                          : cv::StereoSGBM::MODE_SGBM;
    auto sgbm = cv::StereoSGBM::create(o.min_disparity_px, o.num_disparities, o.block_size_px, 8 * channels * area,
                                       32 * channels * area, within_pass_check(), 0, o.uniqueness_ratio, 0, 0, mode);
    sgbm->compute(left, right, raw);
  }
  return pad > 0 ? raw.colRange(pad, raw.cols).clone() : raw;
}

void DisparityMatcher::check_pair(const cv::Mat& left, const cv::Mat& right, const std::string& where) const {
  if (left.empty() || right.empty())
    throw InputError(where + ": the " + std::string(left.empty() ? "left" : "right") + " image is empty");
  if (left.size() != right.size())
    throw InputError(where + ": the left image is " + size_text(left) + " px, the right " + size_text(right) +
                     " px; a rectified pair has one size");
  if (left.type() != right.type())
    throw InputError(where + ": the left image is " + type_text(left) + ", the right " + type_text(right) +
                     "; both must be the same type");
  if (left.type() != CV_8UC3 && left.type() != CV_8UC1)
    throw InputError(where + ": images of type " + type_text(left) + "; expected 8-bit BGR (CV_8UC3) or grey (CV_8UC1)");
  const MatcherOptions& o = options_;
  if (o.block_size_px > std::min(left.cols, left.rows) || o.min_disparity_px + o.num_disparities >= left.cols)
    throw InputError(where + ": the images (" + size_text(left) + " px) are too small for block_size_px " +
                     std::to_string(o.block_size_px) + " and disparities up to " +
                     std::to_string(o.min_disparity_px + o.num_disparities - 1) + " px");
}

DisparityPair DisparityMatcher::match(const cv::Mat& left, const cv::Mat& right, const std::string& where) const {
  check_pair(left, right, where);
  const MatcherOptions& o = options_;
  DisparityPair pair;
  try {
    to_px(raw_disparity(left, right), o.min_disparity_px, pair.left_px, pair.valid_left);
    if (!o.right_pass) {  // one pass: no right view's disparities, its check was OpenCV's
      pair.right_px = cv::Mat::zeros(left.size(), CV_32FC1);
      pair.valid_right = cv::Mat::zeros(left.size(), CV_8UC1);
      return pair;
    }
    // The right view's disparities: the mirrored pair, right image as the reference.
    cv::Mat left_mirror, right_mirror;
    cv::flip(right, left_mirror, 1);
    cv::flip(left, right_mirror, 1);
    cv::Mat mirrored = raw_disparity(left_mirror, right_mirror);
    cv::flip(mirrored, mirrored, 1);
    to_px(mirrored, o.min_disparity_px, pair.right_px, pair.valid_right);
  } catch (const cv::Exception& e) {
    throw InputError(where + ": OpenCV's matcher refused the pair: " + e.err);
  }
  if (o.lr_check) check_left_right(pair, o.max_lr_difference_px);
  return pair;
}

DisparityPair DisparityMatcher::match_region(const cv::Mat& left, const cv::Mat& right, cv::Rect region,
                                             const std::string& where) const {
  check_pair(left, right, where);
  const MatcherOptions& o = options_;
  if (o.right_pass)
    throw InputError(where + ": matching a region is one pass, without the right view's (right_pass: false)");
  DisparityPair pair{cv::Mat::zeros(left.size(), CV_32FC1), cv::Mat::zeros(left.size(), CV_32FC1),
                     cv::Mat::zeros(left.size(), CV_8UC1), cv::Mat::zeros(left.size(), CV_8UC1)};
  region &= cv::Rect(0, 0, left.cols, left.rows);
  if (region.empty()) return pair;
  // The region's rows (at least a block high), and its columns with the
  // search range to their left, where their matches lie.
  const int reach = o.min_disparity_px + o.num_disparities;
  const int grow = std::max(0, o.block_size_px - region.height);
  const int y0 = std::max(0, region.y - grow / 2), y1 = std::min(left.rows, region.y + region.height + (grow + 1) / 2);
  const int x0 = std::max(0, region.x - reach), x1 = region.x + region.width;
  if (!o.full_width && x1 <= reach) return pair;  // all in the columns OpenCV leaves unmatched
  const cv::Rect crop(x0, y0, std::max(x1 - x0, reach + 1), y1 - y0);
  cv::Mat px, valid;
  try {
    to_px(raw_disparity(left(crop & cv::Rect(0, 0, left.cols, left.rows)).clone(),
                        right(crop & cv::Rect(0, 0, left.cols, left.rows)).clone()),
          o.min_disparity_px, px, valid);
  } catch (const cv::Exception& e) {
    throw InputError(where + ": OpenCV's matcher refused the pair: " + e.err);
  }
  const cv::Rect kept(region.x - x0, region.y - y0, region.width, region.height);
  px(kept).copyTo(pair.left_px(region));
  valid(kept).copyTo(pair.valid_left(region));
  return pair;
}

void check_left_right(DisparityPair& pair, double max_difference_px) {
  const int w = pair.left_px.cols;
  // Read from copies: each map's check uses the other before its own pruning.
  const cv::Mat left = pair.left_px.clone(), right = pair.right_px.clone();
  const cv::Mat valid_left = pair.valid_left.clone(), valid_right = pair.valid_right.clone();
  for (int y = 0; y < left.rows; ++y) {
    const float *dl = left.ptr<float>(y), *dr = right.ptr<float>(y);
    const std::uint8_t *vl = valid_left.ptr<std::uint8_t>(y), *vr = valid_right.ptr<std::uint8_t>(y);
    auto* out_l = pair.left_px.ptr<float>(y);
    auto* out_r = pair.right_px.ptr<float>(y);
    auto* ok_l = pair.valid_left.ptr<std::uint8_t>(y);
    auto* ok_r = pair.valid_right.ptr<std::uint8_t>(y);
    for (int x = 0; x < w; ++x) {
      if (vl[x]) {
        const int xr = static_cast<int>(std::lround(x - dl[x]));
        if (xr < 0 || xr >= w || !vr[xr] || std::abs(dr[xr] - dl[x]) > max_difference_px) ok_l[x] = 0, out_l[x] = 0;
      }
      if (vr[x]) {
        const int xl = static_cast<int>(std::lround(x + dr[x]));
        if (xl < 0 || xl >= w || !vl[xl] || std::abs(dl[xl] - dr[x]) > max_difference_px) ok_r[x] = 0, out_r[x] = 0;
      }
    }
  }
}

}  // namespace touchcloud::imaging
