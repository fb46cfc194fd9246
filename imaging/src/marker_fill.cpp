#include "touchcloud/imaging/marker_fill.hpp"

#include <opencv2/imgproc.hpp>
#include <opencv2/photo.hpp>

#include "touchcloud/error.hpp"

namespace touchcloud::imaging {

MarkerFill::MarkerFill(MarkerFillOptions options) : options_(options), detector_(options.detector) {
  if (!(options_.margin_px >= 0)) throw ParameterError("margin_px", "must be at least 0");
  if (!(options_.inpaint_radius_px > 0)) throw ParameterError("inpaint_radius_px", "must be above 0");
  if (!(options_.ink_grey > 0)) throw ParameterError("ink_grey", "must be above 0");
  const int w = detector_.options().background_window();
  window_ = cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(w, w));
}

void MarkerFill::add_discs(const std::vector<Marker>& markers, cv::Mat& mask) const {
  const double radius = 0.5 * options_.detector.max_diameter_px + options_.margin_px;
  constexpr int kShift = 4;  // sub-pixel centres for cv::circle
  for (const Marker& m : markers)
    cv::circle(mask, cv::Point(cvRound(m.centre_px.x() * (1 << kShift)), cvRound(m.centre_px.y() * (1 << kShift))),
               cvRound(radius * (1 << kShift)), cv::Scalar(255), cv::FILLED, cv::LINE_8, kShift);
}

void MarkerFill::ink(const cv::Mat& bgr, cv::Mat& out) {
  cv::cvtColor(bgr, grey_, cv::COLOR_BGR2GRAY);
  cv::morphologyEx(grey_, closed_, cv::MORPH_CLOSE, window_);
  cv::subtract(closed_, grey_, out);
  cv::threshold(out, out, options_.ink_grey, 255, cv::THRESH_BINARY);
}

FilledPair MarkerFill::fill(const cv::Mat& image, const cv::Mat& reference) {
  CV_Assert(image.type() == CV_8UC3 && reference.type() == CV_8UC3 && image.size() == reference.size());
  // The same reference as last time (the same pixels): its dots are known.
  const bool same_reference = reference_seen_.size() == reference.size() &&
                              cv::norm(reference_seen_, reference, cv::NORM_INF) == 0;
  if (!same_reference) {
    reference_dots_ = detector_.detect(reference, "reference");
    reference.copyTo(reference_seen_);
  }
  const std::vector<Marker> dots = detector_.detect(image, "image");
  discs_.create(image.size(), CV_8UC1);
  discs_.setTo(0);
  add_discs(dots, discs_);
  add_discs(reference_dots_, discs_);
  // Within the discs, the pixels darker than the gel around them (either image), one pixel wider.
  ink(image, ink_image_);
  ink(reference, ink_reference_);
  cv::bitwise_or(ink_image_, ink_reference_, mask_);
  cv::bitwise_and(mask_, discs_, mask_);
  cv::dilate(mask_, mask_, cv::Mat());
  FilledPair out;
  out.image_markers = dots.size();
  out.reference_markers = reference_dots_.size();
  out.mask = mask_;
  if (dots.empty() && reference_dots_.empty()) {
    out.image = image;
    out.reference = reference;
    return out;
  }
  cv::inpaint(image, mask_, image_out_, options_.inpaint_radius_px, cv::INPAINT_TELEA);
  cv::inpaint(reference, mask_, reference_out_, options_.inpaint_radius_px, cv::INPAINT_TELEA);
  out.image = image_out_;
  out.reference = reference_out_;
  return out;
}

}  // namespace touchcloud::imaging
