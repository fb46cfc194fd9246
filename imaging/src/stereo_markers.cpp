#include "touchcloud/imaging/stereo_markers.hpp"

#include <exception>

#include <opencv2/core/utility.hpp>

#include "touchcloud/error.hpp"

namespace touchcloud::imaging {

namespace {

std::string size_px_text(const cv::Mat& image) {
  return std::to_string(image.cols) + " x " + std::to_string(image.rows) + " px";
}

}  // namespace

MarkerSet StereoMarkerDetector::detect(const StereoFramePtr& frame, const std::string& input) {
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
    throw InputError(where + ": the left image is " + size_px_text(frame->left) + " but the right image is " +
                     size_px_text(frame->right));

  MarkerSet set;
  std::exception_ptr failed[2];  // an exception must not leave a parallel body
  cv::parallel_for_(cv::Range(0, 2), [&](const cv::Range& views) {
    for (int v = views.start; v < views.end; ++v) try {
        if (v == 0) set.left = left_.detect(frame->left, where + ", left image");
        else set.right = right_.detect(frame->right, where + ", right image");
      } catch (...) {
        failed[v] = std::current_exception();
      }
  });
  for (const auto& f : failed)
    if (f) std::rethrow_exception(f);
  set.timestamp_s = frame->timestamp_s;
  return set;
}

}  // namespace touchcloud::imaging
