#include "touchcloud/plugin_kit/camera/stereo_feed.hpp"

#include <algorithm>
#include <cmath>

#include "touchcloud/error.hpp"

namespace touchcloud::camera {

namespace {

std::string size_text(const cv::Mat& image) {
  return std::to_string(image.cols) + " x " + std::to_string(image.rows) + " px";
}

std::string source_text(const FrameFeed& feed) {
  return std::string(describe(feed.source_kind())) + " " + feed.source();
}

}  // namespace

StereoFeed::StereoFeed(std::unique_ptr<FrameFeed> left, std::unique_ptr<FrameFeed> right, double max_skew_ms)
    : left_(std::move(left)), right_(std::move(right)), max_skew_ms_(max_skew_ms) {}

StereoFeed::StereoFeed(std::unique_ptr<FrameFeed> side_by_side) : left_(std::move(side_by_side)) {}

std::pair<cv::Mat, cv::Mat> StereoFeed::split(const cv::Mat& frame, const std::string& what) {
  if (frame.cols % 2 != 0)
    throw InputError(what + " is " + size_text(frame) +
                     ": a side-by-side frame needs an even width, the left view in its left half");
  const int half = frame.cols / 2;
  return {frame.colRange(0, half).clone(), frame.colRange(half, frame.cols).clone()};
}

std::optional<Shot> StereoFeed::take(FrameFeed& feed, SequenceGaps& gaps, double timeout_s) {
  std::optional<Shot> shot = feed.next(timeout_s);
  if (shot) gaps.see(shot->stamp.sequence, feed.first_sequence());
  return shot;
}

std::optional<ShotPair> StereoFeed::next(double timeout_s) {
  if (!right_) {
    std::optional<Shot> shot = take(*left_, left_gaps_, timeout_s);
    if (!shot) return std::nullopt;
    ShotPair pair{*shot, *shot, 0.0};
    std::tie(pair.left.image, pair.right.image) =
        split(shot->image, "the " + source_text(*left_) + "'s frame " + std::to_string(shot->stamp.sequence));
    return pair;
  }
  for (;;) {
    if (!left_held_) left_held_ = take(*left_, left_gaps_, timeout_s);
    if (!left_held_) return std::nullopt;
    if (!right_held_) right_held_ = take(*right_, right_gaps_, timeout_s);
    if (!right_held_) return std::nullopt;
    const double skew_ms = (right_held_->clock_s - left_held_->clock_s) * 1000.0;
    if (std::abs(skew_ms) > max_skew_ms_) {
      refusals_.push_back({left_held_->clock_s, right_held_->clock_s});
      ++refused_;
      (skew_ms > 0 ? left_held_ : right_held_).reset();  // the older frame has no partner left
      continue;
    }
    ShotPair pair{std::move(*left_held_), std::move(*right_held_), skew_ms};
    left_held_.reset(), right_held_.reset();
    if (pair.left.image.size() != pair.right.image.size())
      throw InputError("the right " + source_text(*right_) + "'s frame " + std::to_string(pair.right.stamp.sequence) +
                       " is " + size_text(pair.right.image) + " but the left " + source_text(*left_) + "'s is " +
                       size_text(pair.left.image));
    pair.left.captured_at = pair.right.captured_at = std::max(pair.left.captured_at, pair.right.captured_at);
    return pair;
  }
}

std::optional<bool> StereoFeed::last(const ShotPair& pair) const {
  if (pair.left.last || pair.right.last) return true;
  const std::optional<double>&left = pair.left.next_clock_s, &right = pair.right.next_clock_s;
  if (!right_) return left ? std::optional<bool>(false) : std::nullopt;
  if (left && right && std::abs(*right - *left) * 1000.0 <= max_skew_ms_) return false;
  return std::nullopt;
}

std::vector<RefusedPair> StereoFeed::take_refusals() { return std::exchange(refusals_, {}); }

std::int64_t StereoFeed::captured() const { return left_->captured() + (right_ ? right_->captured() : 0); }

}  // namespace touchcloud::camera
