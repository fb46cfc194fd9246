#include "touchcloud/simulation/objects/indenters.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace touchcloud::simulation {

namespace {
// The height of a sphere's (or a cylinder's) cross-section `distance` from its axis, at least the table's.
double round_top(double radius, double top, double distance) {
  if (distance >= radius) return 0.0;
  return std::max(0.0, top - radius + std::sqrt(radius * radius - distance * distance));
}
}  // namespace

BallIndenter::BallIndenter(double radius_mm, const Eigen::Vector2d& centre_mm, double top_mm)
    : radius_(radius_mm), top_(top_mm), centre_(centre_mm) {}

double BallIndenter::height_mm(const Eigen::Vector2d& xy_mm) const {
  return round_top(radius_, top_, (xy_mm - centre_).norm());
}

RodIndenter::RodIndenter(double radius_mm, const Eigen::Vector2d& from_mm, const Eigen::Vector2d& to_mm,
                         double top_mm)
    : radius_(radius_mm), top_(top_mm), from_(from_mm), to_(to_mm) {}

double RodIndenter::height_mm(const Eigen::Vector2d& xy_mm) const {
  const Eigen::Vector2d axis = to_ - from_;
  const double t = std::clamp((xy_mm - from_).dot(axis) / axis.squaredNorm(), 0.0, 1.0);
  return round_top(radius_, top_, (xy_mm - (from_ + t * axis)).norm());
}

TextRelief::TextRelief(const std::string& text, double letter_height_mm, double stroke_mm, double relief_mm,
                       double edge_sigma_mm, const Eigen::Vector2d& centre_mm) {
  const int font = cv::FONT_HERSHEY_SIMPLEX;
  const double scale = letter_height_mm / kPitchMm / 22.0;  // the simplex capital is about 22 units tall at scale 1
  const int thickness = std::max(1, static_cast<int>(std::lround(stroke_mm / kPitchMm)));
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, font, scale, thickness, &baseline);
  const int margin = static_cast<int>(std::ceil(4 * edge_sigma_mm / kPitchMm)) + thickness;
  cv::Mat ink(size.height + baseline + 2 * margin, size.width + 2 * margin, CV_8UC1, cv::Scalar(0));
  cv::putText(ink, text, {margin, margin + size.height}, font, scale, cv::Scalar(255), thickness, cv::LINE_AA);
  ink.convertTo(height_, CV_32FC1, relief_mm / 255.0);
  cv::GaussianBlur(height_, height_, cv::Size(0, 0), edge_sigma_mm / kPitchMm);
  // Image rows run down; the base's y runs up: flip so the text reads from above.
  cv::flip(height_, height_, 0);
  double most = 0;
  cv::minMaxLoc(height_, nullptr, &most);
  top_ = most;
  origin_ = centre_mm - 0.5 * kPitchMm * Eigen::Vector2d(height_.cols - 1, height_.rows - 1);
}

double TextRelief::height_mm(const Eigen::Vector2d& xy_mm) const {
  const Eigen::Vector2d at = (xy_mm - origin_) / kPitchMm;
  const int u = static_cast<int>(std::floor(at.x())), v = static_cast<int>(std::floor(at.y()));
  if (u < 0 || v < 0 || u + 1 >= height_.cols || v + 1 >= height_.rows) return 0.0;
  const double fu = at.x() - u, fv = at.y() - v;
  const auto h = [&](int du, int dv) { return static_cast<double>(height_.at<float>(v + dv, u + du)); };
  return (1 - fv) * ((1 - fu) * h(0, 0) + fu * h(1, 0)) + fv * ((1 - fu) * h(0, 1) + fu * h(1, 1));
}

}  // namespace touchcloud::simulation
