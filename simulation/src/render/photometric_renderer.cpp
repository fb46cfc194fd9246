#include "touchcloud/simulation/render/photometric_renderer.hpp"

#include <algorithm>
#include <cmath>

namespace touchcloud::simulation {

namespace {
std::uint8_t grey(double value) { return static_cast<std::uint8_t>(std::clamp(std::lround(value), 0L, 255L)); }
}  // namespace

PhotometricRenderer::PhotometricRenderer(const sensor::GelSightSensor& sensor)
    : sensor_(sensor), flat_(shading(Eigen::Vector3d::UnitZ())) {
  const int w = sensor_.width_px, h = sensor_.height_px;
  background_f_.create(h, w, CV_32FC3);
  background_.create(h, w, CV_8UC3);
  const double cx = 0.5 * (w - 1), cy = 0.5 * (h - 1), corner2 = cx * cx + cy * cy;
  const Eigen::Vector3d lit = sensor_.ambient_rgb + flat_;
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const double fall = 1 - sensor_.vignetting * ((u - cx) * (u - cx) + (v - cy) * (v - cy)) / corner2;
      const Eigen::Vector3d rgb = lit * fall;
      background_f_.at<cv::Vec3f>(v, u) = cv::Vec3f(float(rgb[2]), float(rgb[1]), float(rgb[0]));
      background_.at<cv::Vec3b>(v, u) = cv::Vec3b(grey(rgb[2]), grey(rgb[1]), grey(rgb[0]));
    }
}

Eigen::Vector3d PhotometricRenderer::shading(const Eigen::Vector3d& n) const {
  Eigen::Vector3d rgb = Eigen::Vector3d::Zero();
  for (const auto& light : sensor_.lights) {
    const double nl = n.dot(light.direction);
    if (!(nl > 0)) continue;
    double amount = sensor_.diffuse * nl;
    const double rz = 2 * nl * n.z() - light.direction.z();  // the mirrored light's z: towards the camera
    if (sensor_.specular > 0 && rz > 0) amount += sensor_.specular * std::pow(rz, sensor_.shininess);
    rgb += amount * light.colour_rgb;
  }
  return rgb;
}

cv::Mat PhotometricRenderer::render(const cv::Mat& height_mm) const {
  CV_Assert(height_mm.type() == CV_32FC1 && height_mm.size() == background_.size());
  cv::Mat image = background_.clone();
  const int w = height_mm.cols, h = height_mm.rows;
  const double inv = 1.0 / sensor_.mm_per_px;
  for (int v = 0; v < h; ++v) {
    const float* row = height_mm.ptr<float>(v);
    const float* up = height_mm.ptr<float>(std::max(v - 1, 0));
    const float* down = height_mm.ptr<float>(std::min(v + 1, h - 1));
    const double dv = (v == 0 || v == h - 1) ? inv : 0.5 * inv;
    for (int u = 0; u < w; ++u) {
      const int l = std::max(u - 1, 0), r = std::min(u + 1, w - 1);
      const double gx = (row[r] - row[l]) * ((r - l) == 2 ? 0.5 * inv : inv);
      const double gy = (down[u] - up[u]) * dv;
      if (gx == 0 && gy == 0) continue;  // the flat gel: the background itself
      const Eigen::Vector3d rgb = shading(normal(gx, gy)) - flat_;
      const cv::Vec3f& b = background_f_.at<cv::Vec3f>(v, u);
      image.at<cv::Vec3b>(v, u) = cv::Vec3b(grey(b[0] + rgb[2]), grey(b[1] + rgb[1]), grey(b[2] + rgb[0]));
    }
  }
  return image;
}

}  // namespace touchcloud::simulation
