#include "touchcloud/simulation/render/gel_markers.hpp"

#include <algorithm>
#include <cmath>

namespace touchcloud::simulation {

namespace {

// Bilinear height at (x, y) px, clamped to the image.
double height_at(const cv::Mat& h, double x, double y) {
  x = std::clamp(x, 0.0, h.cols - 1.0);
  y = std::clamp(y, 0.0, h.rows - 1.0);
  const int u = std::min(static_cast<int>(x), h.cols - 2), v = std::min(static_cast<int>(y), h.rows - 2);
  const double a = x - u, b = y - v;
  return (1 - b) * ((1 - a) * h.at<float>(v, u) + a * h.at<float>(v, u + 1)) +
         b * ((1 - a) * h.at<float>(v + 1, u) + a * h.at<float>(v + 1, u + 1));
}

}  // namespace

GelMarkers::GelMarkers(const sensor::GelSightSensor& sensor, GelMarkerOptions options)
    : options_(options), mm_per_px_(sensor.mm_per_px), diameter_px_(options.diameter_mm / sensor.mm_per_px) {
  const double pitch_px = options_.pitch_mm / mm_per_px_, r = 0.5 * diameter_px_;
  const double cx = 0.5 * (sensor.width_px - 1), cy = 0.5 * (sensor.height_px - 1);
  const int nx = static_cast<int>(std::floor((cx - r) / pitch_px)), ny = static_cast<int>(std::floor((cy - r) / pitch_px));
  for (int j = -ny; j <= ny; ++j)
    for (int i = -nx; i <= nx; ++i) rest_px_.emplace_back(cx + i * pitch_px, cy + j * pitch_px);
}

std::vector<cv::Point2d> GelMarkers::moved_px(const cv::Mat& height_mm) const {
  CV_Assert(height_mm.type() == CV_32FC1 && height_mm.cols >= 2 && height_mm.rows >= 2);
  // Slope (mm/mm) by central differences one pixel either side; shift in px.
  const double gain = options_.shift_per_slope_mm / mm_per_px_ / (2 * mm_per_px_);
  std::vector<cv::Point2d> out;
  out.reserve(rest_px_.size());
  for (const cv::Point2d& p : rest_px_) {
    const double gx = height_at(height_mm, p.x + 1, p.y) - height_at(height_mm, p.x - 1, p.y);
    const double gy = height_at(height_mm, p.x, p.y + 1) - height_at(height_mm, p.x, p.y - 1);
    out.emplace_back(p.x - gain * gx, p.y - gain * gy);
  }
  return out;
}

void GelMarkers::draw(cv::Mat& bgr, const std::vector<cv::Point2d>& centres_px) const {
  CV_Assert(bgr.type() == CV_8UC3);
  constexpr int kSamples = 4;
  const double r = 0.5 * diameter_px_, r2 = r * r;
  for (const cv::Point2d& c : centres_px) {
    const int u0 = std::max(0, static_cast<int>(std::floor(c.x - r - 1))), u1 = std::min(bgr.cols - 1, static_cast<int>(std::ceil(c.x + r + 1)));
    const int v0 = std::max(0, static_cast<int>(std::floor(c.y - r - 1))), v1 = std::min(bgr.rows - 1, static_cast<int>(std::ceil(c.y + r + 1)));
    for (int v = v0; v <= v1; ++v)
      for (int u = u0; u <= u1; ++u) {
        int inside = 0;
        for (int sy = 0; sy < kSamples; ++sy)
          for (int sx = 0; sx < kSamples; ++sx) {
            const double dx = u - 0.5 + (sx + 0.5) / kSamples - c.x, dy = v - 0.5 + (sy + 0.5) / kSamples - c.y;
            inside += dx * dx + dy * dy <= r2;
          }
        if (inside == 0) continue;
        const double keep = 1 - options_.darkness * inside / double(kSamples * kSamples);
        cv::Vec3b& px = bgr.at<cv::Vec3b>(v, u);
        for (int k = 0; k < 3; ++k) px[k] = static_cast<std::uint8_t>(std::lround(px[k] * keep));
      }
  }
}

}  // namespace touchcloud::simulation
