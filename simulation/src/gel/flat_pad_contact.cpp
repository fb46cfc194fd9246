#include "touchcloud/simulation/gel/flat_pad_contact.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace touchcloud::simulation {

namespace {

// out[i] = max_j in[j] w[|i - j|] along one line of `n` values at `stride`.
void max_product_line(const float* in, float* out, int n, int stride, const std::vector<float>& w) {
  const int reach = static_cast<int>(w.size()) - 1;
  for (int i = 0; i < n; ++i) out[i * stride] = 0;
  for (int j = 0; j < n; ++j) {
    const float v = in[j * stride];
    if (!(v > 0)) continue;
    for (int i = std::max(0, j - reach); i <= std::min(n - 1, j + reach); ++i)
      out[i * stride] = std::max(out[i * stride], v * w[std::abs(i - j)]);
  }
}

void spread(cv::Mat& height, double sigma_px) {
  const int reach = static_cast<int>(std::ceil(6 * sigma_px));
  std::vector<float> w(reach + 1);
  for (int d = 0; d <= reach; ++d) w[d] = static_cast<float>(std::exp(-d * d / (2 * sigma_px * sigma_px)));
  cv::Mat rows(height.size(), CV_32FC1), both(height.size(), CV_32FC1);
  for (int v = 0; v < height.rows; ++v) max_product_line(height.ptr<float>(v), rows.ptr<float>(v), height.cols, 1, w);
  for (int u = 0; u < height.cols; ++u)
    max_product_line(rows.ptr<float>(0) + u, both.ptr<float>(0) + u, height.rows, height.cols, w);
  // Contact points keep their own height (the object holds them there).
  for (int v = 0; v < height.rows; ++v) {
    const float* own = height.ptr<float>(v);
    float* out = both.ptr<float>(v);
    for (int u = 0; u < height.cols; ++u)
      if (own[u] > 0) out[u] = own[u];
  }
  height = both;
}

}  // namespace

void press_pad(const sensor::GelSightSensor& s, const Eigen::Isometry3d& base_from_sensor, const ObjectSurface& object,
               const GelContactOptions& options, PadPress& press) {
  press.height_mm.create(s.height_px, s.width_px, CV_32FC1);
  press.height_mm.setTo(0);
  press.overlapping_px = 0;
  press.max_overlap_mm = 0;
  const double cx = 0.5 * (s.width_px - 1), cy = 0.5 * (s.height_px - 1);
  for (int v = 0; v < s.height_px; ++v) {
    float* row = press.height_mm.ptr<float>(v);
    for (int u = 0; u < s.width_px; ++u) {
      const Eigen::Vector3d p =
          base_from_sensor * Eigen::Vector3d((u - cx) * s.mm_per_px, (v - cy) * s.mm_per_px, s.gel_thickness_mm);
      const double overlap = object.overlap_mm(p.head<2>(), p.z());
      if (!(overlap > 0)) continue;
      ++press.overlapping_px;
      press.max_overlap_mm = std::max(press.max_overlap_mm, overlap);
      if (options.contact) row[u] = static_cast<float>(std::min(overlap, s.gel_thickness_mm));
    }
  }
  if (options.contact && options.elastic_spread && press.overlapping_px > 0)
    spread(press.height_mm, options.spread_sigma_mm / s.mm_per_px);
}

}  // namespace touchcloud::simulation
