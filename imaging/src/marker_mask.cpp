#include "touchcloud/imaging/marker_mask.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <opencv2/imgproc.hpp>

#include "touchcloud/error.hpp"

namespace touchcloud::imaging {

MarkerMask::MarkerMask(MarkerMaskOptions options) : options_(options), detector_(options.detector) {
  if (!(options_.margin_px >= 0)) throw ParameterError("margin_px", "must be at least 0");
  if (!(options_.ink_grey > 0)) throw ParameterError("ink_grey", "must be above 0");
  const int w = detector_.options().background_window();
  window_ = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(w, w));  // separable: fast
}

void MarkerMask::add_discs(const std::vector<Marker>& markers, double radius, cv::Mat& mask) const {
  constexpr int kShift = 4;  // sub-pixel centres for cv::circle
  for (const Marker& m : markers)
    cv::circle(mask, cv::Point(cvRound(m.centre_px.x() * (1 << kShift)), cvRound(m.centre_px.y() * (1 << kShift))),
               cvRound(radius * (1 << kShift)), cv::Scalar(255), cv::FILLED, cv::LINE_8, kShift);
}

void MarkerMask::ink(const cv::Mat& bgr, cv::Mat& out) {
  cv::cvtColor(bgr, grey_, cv::COLOR_BGR2GRAY);
  cv::morphologyEx(grey_, closed_, cv::MORPH_CLOSE, window_);
  cv::subtract(closed_, grey_, out);
  cv::threshold(out, out, options_.ink_grey, 255, cv::THRESH_BINARY);
}

void MarkerMask::dot_mask(const cv::Mat& bgr, const std::vector<Marker>& dots, cv::Mat& mask) {
  discs_.create(bgr.size(), CV_8UC1);
  discs_.setTo(0);
  add_discs(dots, disc_radius(), discs_);
  ink(bgr, mask);
  cv::bitwise_and(mask, discs_, mask);
  cv::dilate(mask, mask, cv::Mat());
}

void MarkerMask::add_lost_dots(const cv::Mat& image, const std::vector<Marker>& dots, cv::Mat& mask) {
  const double reach = options_.detector.max_diameter_px, reach2 = reach * reach;
  lost_.clear();
  for (const Marker& r : reference_dots_)
    if (std::none_of(dots.begin(), dots.end(),
                     [&](const Marker& d) { return (d.centre_px - r.centre_px).squaredNorm() <= reach2; }))
      lost_.push_back(r);
  if (lost_.empty()) return;
  discs_.setTo(0);
  add_discs(lost_, disc_radius() + reach, discs_);
  // Ink: darker than the closing by kInkShare of it in every channel. The
  // press's shading darkens one or two channels and lightens another; the
  // ink darkens all three alike.
  constexpr double kInkShare = 0.4;
  cv::morphologyEx(image, closed_colour_, cv::MORPH_CLOSE, window_);
  lost_ink_.create(image.size(), CV_8UC1);
  for (int v = 0; v < image.rows; ++v) {
    const cv::Vec3b* a = image.ptr<cv::Vec3b>(v);
    const cv::Vec3b* c = closed_colour_.ptr<cv::Vec3b>(v);
    const std::uint8_t* disc = discs_.ptr<std::uint8_t>(v);
    std::uint8_t* ink = lost_ink_.ptr<std::uint8_t>(v);
    for (int u = 0; u < image.cols; ++u) {
      bool dark = disc[u] != 0;
      for (int k = 0; k < 3 && dark; ++k) dark = a[u][k] < (1 - kInkShare) * c[u][k];
      ink[u] = dark ? 255 : 0;
    }
  }
  cv::dilate(lost_ink_, lost_ink_, cv::Mat());
  cv::bitwise_or(mask, lost_ink_, mask);
}

MarkerMasks MarkerMask::masks(const cv::Mat& image, const cv::Mat& reference) {
  CV_Assert(image.type() == CV_8UC3 && reference.type() == CV_8UC3 && image.size() == reference.size());
  // The same reference as last time (the same pixels): its dots and mask are known.
  bool same_reference = reference_seen_.size() == reference.size();
  const std::size_t row_bytes = reference.cols * reference.elemSize();
  for (int v = 0; same_reference && v < reference.rows; ++v)
    same_reference = std::memcmp(reference_seen_.ptr(v), reference.ptr(v), row_bytes) == 0;
  if (!same_reference) {
    reference.copyTo(reference_seen_);
    reference_dots_ = detector_.detect(reference, "reference");
    dot_mask(reference, reference_dots_, reference_mask_);
  }
  const std::vector<Marker> dots = detector_.detect(image, "image");
  dot_mask(image, dots, mask_);
  add_lost_dots(image, dots, mask_);
  cv::bitwise_or(mask_, reference_mask_, union_);
  MarkerMasks out;
  out.excluded.mask = union_;
  // A window reaching past the disc a dot may cover (and the pixel it was grown by).
  out.excluded.window_px = 2 * static_cast<int>(std::ceil(disc_radius())) + 3;
  out.image_markers = dots.size();
  out.reference_markers = reference_dots_.size();
  return out;
}

}  // namespace touchcloud::imaging
