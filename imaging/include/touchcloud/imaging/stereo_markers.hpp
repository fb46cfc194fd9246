// Markers in both views of a stereo frame, left unmatched (a later stage
// pairs them). The two views are detected side by side (cv::parallel_for_,
// so cv::setNumThreads(1) keeps it on one core), each with its own detector.
#pragma once

#include "touchcloud/imaging/marker_detector.hpp"
#include "touchcloud/types/stereo_frame.hpp"

namespace touchcloud::imaging {

class StereoMarkerDetector {
 public:
  explicit StereoMarkerDetector(const MarkerDetectorOptions& options) : left_(options), right_(options) {}
  const MarkerDetectorOptions& options() const { return left_.options(); }

  // Detects the markers of the left and right images and copies the frame's
  // timestamp; `matches` stays empty. Throws InputError naming the input
  // (`input` is its name in messages) when the frame is missing, an image is
  // empty or of a type the detector does not take, or the two sizes differ.
  MarkerSet detect(const StereoFramePtr& frame, const std::string& input = "frame");

 private:
  MarkerDetector left_, right_;
};

}  // namespace touchcloud::imaging
