// Stereo pairs from two cameras paired by capture time, or from one camera
// whose frames hold both views side by side. Two cameras' frames are paired
// on their clocks (Shot::clock_s): the two oldest frames form a pair when
// they were captured at most `max_skew_ms` apart; otherwise the pair is
// refused, the older frame is let go (counted) and the next one taken, so a
// camera that lags or loses frames costs refused pairs, never a hang.
#pragma once

#include <memory>
#include <optional>

#include "touchcloud/plugin_kit/camera/frame_feed.hpp"
#include "touchcloud/plugin_kit/camera/frame_tally.hpp"

namespace touchcloud::camera {

struct ShotPair {
  Shot left, right;  // the same size and type
  double skew_ms = 0;  // right's capture time less left's
};

// A refused pair: the two oldest frames' capture times, s on each camera's clock.
struct RefusedPair {
  double left_clock_s = 0, right_clock_s = 0;
};

class StereoFeed {
 public:
  StereoFeed(std::unique_ptr<FrameFeed> left, std::unique_ptr<FrameFeed> right, double max_skew_ms);
  // One camera, the left view in the left half of its frames: InputError
  // for a frame of an odd width (no middle to split at).
  explicit StereoFeed(std::unique_ptr<FrameFeed> side_by_side);

  // The next pair, waiting at most `timeout_s` for each frame; none once a
  // camera has ended. InputError when the two frames differ in size.
  std::optional<ShotPair> next(double timeout_s);

  // Whether `pair` is a recording's last, from what its frames read ahead
  // say (a camera's last frame, or the next frames within the skew: no wait
  // for them to be due); none when only the next pair can tell (the next
  // frames too far apart, or cameras that read nothing ahead).
  std::optional<bool> last(const ShotPair& pair) const;

  std::int64_t refused() const { return refused_; }
  // The refused pairs not yet taken (for a report per call).
  std::vector<RefusedPair> take_refusals();
  // Frames lost before pairing: gaps in either camera's sequence.
  std::int64_t dropped() const { return left_gaps_.dropped() + right_gaps_.dropped(); }
  // Frames both cameras delivered (a side-by-side frame counts once).
  std::int64_t captured() const;
  bool side_by_side() const { return !right_; }

  // A side-by-side frame cut at its middle; InputError naming `what` for an odd width.
  static std::pair<cv::Mat, cv::Mat> split(const cv::Mat& frame, const std::string& what);

 private:
  std::optional<Shot> take(FrameFeed& feed, SequenceGaps& gaps, double timeout_s);

  std::unique_ptr<FrameFeed> left_, right_;
  double max_skew_ms_ = 0;
  std::optional<Shot> left_held_, right_held_;
  SequenceGaps left_gaps_, right_gaps_;
  std::int64_t refused_ = 0;
  std::vector<RefusedPair> refusals_;
};

}  // namespace touchcloud::camera
