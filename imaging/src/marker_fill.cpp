#include "touchcloud/imaging/marker_fill.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <Eigen/Dense>

#include <opencv2/imgproc.hpp>

#include "touchcloud/error.hpp"

namespace touchcloud::imaging {

MarkerFill::MarkerFill(MarkerFillOptions options) : options_(options), detector_(options.detector) {
  if (!(options_.margin_px >= 0)) throw ParameterError("margin_px", "must be at least 0");
  if (!(options_.ring_px >= 1)) throw ParameterError("ring_px", "must be at least 1");
  if (!(options_.ink_grey > 0)) throw ParameterError("ink_grey", "must be above 0");
  const int w = detector_.options().background_window();
  window_ = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(w, w));  // separable: fast
}

void MarkerFill::add_discs(const std::vector<Marker>& markers, cv::Mat& mask) const {
  const double radius = disc_radius();
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

void MarkerFill::dot_mask(const cv::Mat& bgr, const std::vector<Marker>& dots, cv::Mat& mask) {
  discs_.create(bgr.size(), CV_8UC1);
  discs_.setTo(0);
  add_discs(dots, discs_);
  ink(bgr, mask);
  cv::bitwise_and(mask, discs_, mask);
  cv::dilate(mask, mask, cv::Mat());
}

// Per dot: a quadratic in (x, y) per channel, fitted by least squares to
// the unmasked pixels of a ring around the dot's disc, gives its masked
// pixels. Each dot writes its own pixels only (those within its disc), so a
// neighbour's dot reaching into the ring is skipped there (masked) and filled
// by its own fit.
void MarkerFill::fill_dots(const cv::Mat& bgr, const std::vector<Marker>& dots, const cv::Mat& mask, cv::Mat& out) {
  bgr.copyTo(out);
  const double reach = disc_radius() + 1;  // the mask was grown by a pixel
  const double outer = reach + options_.ring_px;
  const int pad = static_cast<int>(std::ceil(outer));
  const double reach2 = reach * reach, outer2 = outer * outer;
  for (const Marker& m : dots) {
    const double cx = m.centre_px.x(), cy = m.centre_px.y();
    const int u0 = std::max(0, static_cast<int>(std::floor(cx)) - pad), u1 = std::min(bgr.cols - 1, static_cast<int>(std::ceil(cx)) + pad);
    const int v0 = std::max(0, static_cast<int>(std::floor(cy)) - pad), v1 = std::min(bgr.rows - 1, static_cast<int>(std::ceil(cy)) + pad);
    Eigen::Matrix<double, 6, 6> ata = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 3> atb = Eigen::Matrix<double, 6, 3>::Zero();
    auto terms = [&](double dx, double dy) {
      Eigen::Matrix<double, 6, 1> t;
      t << 1, dx, dy, dx * dx, dx * dy, dy * dy;
      return t;
    };
    const double scale = 1.0 / outer;  // terms of order 1
    // The columns of row v within `radius2` of the centre (a pixel wider: the
    // distances are tested again).
    auto span = [&](int v, double radius2, int& first, int& last) {
      const double dy = v - cy, half = std::sqrt(std::max(0.0, radius2 - dy * dy));
      first = std::max(u0, static_cast<int>(std::floor(cx - half)) - 1);
      last = std::min(u1, static_cast<int>(std::ceil(cx + half)) + 1);
    };
    int inside = 0;
    for (int v = v0; v <= v1; ++v) {
      int first, last;
      span(v, reach2, first, last);
      const std::uint8_t* row = mask.ptr<std::uint8_t>(v);
      for (int u = first; u <= last; ++u) {
        const double dx = u - cx, dy = v - cy;
        if (dx * dx + dy * dy <= reach2) inside += row[u] != 0;
      }
    }
    if (inside == 0) continue;  // nothing to fill
    int ring = 0;
    for (int v = v0; v <= v1; ++v) {
      int first, last;
      span(v, outer2, first, last);
      const std::uint8_t* row = mask.ptr<std::uint8_t>(v);
      const cv::Vec3b* colour = bgr.ptr<cv::Vec3b>(v);
      for (int u = first; u <= last; ++u) {
        const double dx = u - cx, dy = v - cy, r2 = dx * dx + dy * dy;
        if (r2 <= reach2 || r2 > outer2 || row[u]) continue;
        // The normal equations' lower triangle and right sides, in scalars
        // (Eigen's rank update per pixel was a call, and a vector built
        // per pixel stalls on reading back its halves: the fill's cost).
        const double x = dx * scale, y = dy * scale;
        const double t[6] = {1, x, y, x * x, x * y, y * y};
        const cv::Vec3b& p = colour[u];
        const double c[3] = {static_cast<double>(p[0]), static_cast<double>(p[1]), static_cast<double>(p[2])};
        for (int i = 0; i < 6; ++i) {
          for (int j = i; j < 6; ++j) ata(j, i) += t[i] * t[j];
          for (int k = 0; k < 3; ++k) atb(i, k) += t[i] * c[k];
        }
        ++ring;
      }
    }
    if (ring < 12) continue;  // too little around it (the image's corner)
    const Eigen::Matrix<double, 6, 3> coefficients = ata.selfadjointView<Eigen::Lower>().ldlt().solve(atb);
    for (int v = v0; v <= v1; ++v)
      for (int u = u0; u <= u1; ++u) {
        const double dx = u - cx, dy = v - cy;
        if (dx * dx + dy * dy > reach2 || !mask.at<std::uint8_t>(v, u)) continue;
        const Eigen::RowVector3d c = terms(dx * scale, dy * scale).transpose() * coefficients;
        cv::Vec3b& p = out.at<cv::Vec3b>(v, u);
        for (int k = 0; k < 3; ++k) p[k] = cv::saturate_cast<std::uint8_t>(c[k]);
      }
  }
}

FilledPair MarkerFill::fill(const cv::Mat& image, const cv::Mat& reference) {
  CV_Assert(image.type() == CV_8UC3 && reference.type() == CV_8UC3 && image.size() == reference.size());
  // The same reference as last time (the same pixels): its dots and its fill are known.
  bool same_reference = reference_seen_.size() == reference.size();
  const std::size_t row_bytes = reference.cols * reference.elemSize();
  for (int v = 0; same_reference && v < reference.rows; ++v)
    same_reference = std::memcmp(reference_seen_.ptr(v), reference.ptr(v), row_bytes) == 0;
  if (!same_reference) {
    reference.copyTo(reference_seen_);
    reference_dots_ = detector_.detect(reference, "reference");
    dot_mask(reference, reference_dots_, reference_mask_);
    fill_dots(reference, reference_dots_, reference_mask_, reference_out_);
  }
  const std::vector<Marker> dots = detector_.detect(image, "image");
  dot_mask(image, dots, mask_);
  FilledPair out;
  out.image_markers = dots.size();
  out.reference_markers = reference_dots_.size();
  cv::bitwise_or(mask_, reference_mask_, union_);
  out.mask = union_;
  out.reference = reference_out_;
  if (dots.empty()) {
    out.image = image;
    return out;
  }
  fill_dots(image, dots, mask_, image_out_);
  out.image = image_out_;
  return out;
}

}  // namespace touchcloud::imaging
