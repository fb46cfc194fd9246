#include "touchcloud/imaging/displacement_picture.hpp"

#include <opencv2/imgproc.hpp>

namespace touchcloud::imaging {

cv::Mat draw_displacement(const cv::Mat& image, const DisplacementField& field, double scale) {
  cv::Mat out;
  if (image.channels() == 1) cv::cvtColor(image, out, cv::COLOR_GRAY2BGR);
  else out = image.clone();
  constexpr int kShift = 4;  // sub-pixel ends
  auto fixed = [](const Eigen::Vector2d& p) { return cv::Point(cvRound(p.x() * (1 << kShift)), cvRound(p.y() * (1 << kShift))); };
  for (const MarkerDisplacement& m : field.markers) {
    const Eigen::Vector2d tip = m.rest_px + scale * m.displacement_px;
    if (m.displacement_px.norm() * scale < 1) {
      cv::circle(out, fixed(m.rest_px), 1 << kShift, cv::Scalar(0, 200, 0), 1, cv::LINE_AA, kShift);
      continue;
    }
    cv::arrowedLine(out, fixed(m.rest_px), fixed(tip), cv::Scalar(0, 200, 0), 1, cv::LINE_AA, kShift, 0.3);
  }
  return out;
}

}  // namespace touchcloud::imaging
