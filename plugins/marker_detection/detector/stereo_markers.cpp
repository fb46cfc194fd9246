#include "detector/stereo_markers.hpp"

#include "touchcloud/error.hpp"

namespace touchcloud {

namespace {

std::string size_text(const cv::Mat& image) {
  return std::to_string(image.cols) + " x " + std::to_string(image.rows) + " px";
}

}  // namespace

MarkerSet detect_stereo_markers(MarkerDetector& detector, const StereoFramePtr& frame, const std::string& input) {
  const std::string where = "input '" + input + "'";
  if (!frame) throw InputError(where + ": no stereo frame (null)");
  // Check both images before any work, so the message names the first bad one.
  for (const auto& [image, side] : {std::pair{&frame->left, "left"}, std::pair{&frame->right, "right"}}) {
    if (image->empty()) throw InputError(where + ": the " + side + " image is empty");
    if (image->type() != CV_8UC1 && image->type() != CV_8UC3)
      throw InputError(where + ": the " + side + " image is " + image_type_name(*image) +
                       "; marker detection takes 8-bit grey (CV_8UC1) or BGR (CV_8UC3) images");
  }
  if (frame->left.size() != frame->right.size())
    throw InputError(where + ": the left image is " + size_text(frame->left) + " but the right image is " +
                     size_text(frame->right));

  MarkerSet set;
  set.left = detector.detect(frame->left, where + ", left image");
  set.right = detector.detect(frame->right, where + ", right image");
  set.timestamp_s = frame->timestamp_s;
  return set;
}

}  // namespace touchcloud
