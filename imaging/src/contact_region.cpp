#include "touchcloud/imaging/contact_region.hpp"

#include <vector>

#include <opencv2/imgproc.hpp>

namespace touchcloud::imaging {

cv::Mat contact_region(const cv::Mat& view, const cv::Mat& reference, const ContactRegionOptions& o) {
  cv::Mat difference;
  cv::absdiff(view, reference, difference);
  if (difference.channels() == 3) {
    std::vector<cv::Mat> channels;
    cv::split(difference, channels);
    difference = cv::max(cv::max(channels[0], channels[1]), channels[2]);
  }
  if (o.smoothing_px > 1) cv::blur(difference, difference, cv::Size(o.smoothing_px, o.smoothing_px));
  cv::Mat mask = difference > o.threshold_grey;
  if (o.cleanup_px > 1) {
    const cv::Mat square = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(o.cleanup_px, o.cleanup_px));
    cv::morphologyEx(mask, mask, cv::MORPH_OPEN, square);
    cv::morphologyEx(mask, mask, cv::MORPH_CLOSE, square);
  }
  return mask;
}

}  // namespace touchcloud::imaging
