#include "realistic_markers.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace touchcloud::test {

namespace {

constexpr int kWidthPx = 320, kHeightPx = 240;
constexpr int kSubsamples = 5;  // per pixel side, for each dot's coverage

// Half the dot's extent along x and y.
Eigen::Vector2d half_extent(const TrueDot& d) {
  const double c = std::cos(d.angle_rad), s = std::sin(d.angle_rad);
  const double a2 = d.semi_major_px * d.semi_major_px, b2 = d.semi_minor_px * d.semi_minor_px;
  return {std::sqrt(a2 * c * c + b2 * s * s), std::sqrt(a2 * s * s + b2 * c * c)};
}

// The share of each pixel inside the dot, kept where larger than what
// `coverage` holds (dots that overlap take the darker value).
void draw_coverage(const TrueDot& d, cv::Mat& coverage) {
  const Eigen::Vector2d h = half_extent(d);
  const int x0 = std::max(0, static_cast<int>(std::floor(d.centre_px.x() - h.x()))),
            x1 = std::min(coverage.cols - 1, static_cast<int>(std::ceil(d.centre_px.x() + h.x()))),
            y0 = std::max(0, static_cast<int>(std::floor(d.centre_px.y() - h.y()))),
            y1 = std::min(coverage.rows - 1, static_cast<int>(std::ceil(d.centre_px.y() + h.y())));
  const double c = std::cos(d.angle_rad), s = std::sin(d.angle_rad);
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      int inside = 0;
      for (int j = 0; j < kSubsamples; ++j)
        for (int i = 0; i < kSubsamples; ++i) {
          const double dx = x - 0.5 + (i + 0.5) / kSubsamples - d.centre_px.x();
          const double dy = y - 0.5 + (j + 0.5) / kSubsamples - d.centre_px.y();
          const double u = (c * dx + s * dy) / d.semi_major_px, v = (-s * dx + c * dy) / d.semi_minor_px;
          inside += u * u + v * v <= 1;
        }
      float& p = coverage.at<float>(y, x);
      p = std::max(p, static_cast<float>(inside) / (kSubsamples * kSubsamples));
    }
}

}  // namespace

imaging::MarkerDetectorOptions realistic_detector_options() {
  imaging::MarkerDetectorOptions o;
  o.min_diameter_px = 8;
  o.max_diameter_px = 16;
  o.contrast_grey = 20;
  return o;
}

RealisticImage realistic_marker_image(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
  RealisticImage out;

  // A slightly rotated grid that runs past every border.
  const double spacing = uniform(24, 30), rotation = uniform(-0.06, 0.06);
  const Eigen::Vector2d u = spacing * Eigen::Vector2d(std::cos(rotation), std::sin(rotation));
  const Eigen::Vector2d v(-u.y(), u.x());
  const Eigen::Vector2d origin(uniform(-spacing, 0), uniform(-spacing, 0));
  std::vector<TrueDot> dots;
  const int n = static_cast<int>(std::ceil(std::max(kWidthPx, kHeightPx) / spacing)) + 3;
  for (int j = -1; j < n; ++j)
    for (int i = -1; i < n; ++i) {
      TrueDot d;
      d.centre_px = origin + i * u + j * v + Eigen::Vector2d(uniform(-0.7, 0.7), uniform(-0.7, 0.7));
      const double r = uniform(5.2, 6.8);
      const double ratio = uniform(0, 1) < 0.3 ? uniform(1.1, 1.45) : 1.0;  // seen obliquely or sheared
      d.semi_major_px = r * std::sqrt(ratio), d.semi_minor_px = r / std::sqrt(ratio);
      d.angle_rad = uniform(0, M_PI);
      dots.push_back(d);
    }
  // A few dots pushed against a neighbour (shear under contact): they touch or overlap.
  for (int k = 0; k < 4; ++k) {
    const std::size_t a = std::uniform_int_distribution<std::size_t>(0, dots.size() - 2)(rng);
    if (dots[a].merged || dots[a + 1].merged) continue;
    const double reach = uniform(0.85, 1.05) * (dots[a].semi_minor_px + dots[a + 1].semi_minor_px);
    const Eigen::Vector2d towards = (dots[a + 1].centre_px - dots[a].centre_px).normalized();
    dots[a + 1].centre_px = dots[a].centre_px + reach * towards;
    dots[a].merged = dots[a + 1].merged = true;
  }

  // Ink: each pixel's covered share.
  cv::Mat coverage(kHeightPx, kWidthPx, CV_32F, cv::Scalar(0));
  for (TrueDot& d : dots) {
    const Eigen::Vector2d h = half_extent(d);
    const double lo_x = d.centre_px.x() - h.x(), hi_x = d.centre_px.x() + h.x();
    const double lo_y = d.centre_px.y() - h.y(), hi_y = d.centre_px.y() + h.y();
    if (hi_x <= -0.5 || lo_x >= kWidthPx - 0.5 || hi_y <= -0.5 || lo_y >= kHeightPx - 0.5) continue;
    d.border_gap_px = std::min({lo_x + 0.5, kWidthPx - 0.5 - hi_x, lo_y + 0.5, kHeightPx - 0.5 - hi_y});
    d.cut = d.border_gap_px < 0;
    draw_coverage(d, coverage);
    out.dots.push_back(d);
  }

  // Uneven light: a side-to-side gradient, vignetting and an LED's hot spot.
  const double base = uniform(150, 190), gradient = uniform(-0.5, 0.5), vignetting = uniform(0.2, 0.4);
  const Eigen::Vector2d spot(uniform(0, kWidthPx), uniform(0, kHeightPx));
  const double spot_grey = uniform(20, 50), spot_sigma = uniform(40, 80);
  const double darkness = uniform(0.45, 0.7);  // a dot's share of the light it takes away
  cv::Mat signal(kHeightPx, kWidthPx, CV_32F);
  const double cx = 0.5 * (kWidthPx - 1), cy = 0.5 * (kHeightPx - 1);
  for (int y = 0; y < kHeightPx; ++y)
    for (int x = 0; x < kWidthPx; ++x) {
      const double r2 = ((x - cx) * (x - cx) + (y - cy) * (y - cy)) / (cx * cx + cy * cy);
      const double s2 = (Eigen::Vector2d(x, y) - spot).squaredNorm() / (2 * spot_sigma * spot_sigma);
      const double light = base * (1 + gradient * (x / (kWidthPx - 1.0) - 0.5)) * (1 - vignetting * r2) +
                           spot_grey * std::exp(-s2);
      signal.at<float>(y, x) = static_cast<float>(light * (1 - darkness * coverage.at<float>(y, x)));
    }

  // Defocus, then the sensor's shot noise (electrons: Poisson, here Gaussian
  // with its variance) and read noise, then 8 bits and JPEG.
  out.blur_sigma_px = uniform(0.6, 1.4);
  cv::GaussianBlur(signal, signal, cv::Size(0, 0), out.blur_sigma_px);
  const double electrons_per_grey = uniform(8, 20), read_noise_grey = uniform(1.5, 3.0);
  std::normal_distribution<double> normal(0, 1);
  cv::Mat raw(kHeightPx, kWidthPx, CV_8UC1);
  for (int y = 0; y < kHeightPx; ++y)
    for (int x = 0; x < kWidthPx; ++x) {
      const double s = signal.at<float>(y, x);
      const double sigma = std::sqrt(s / electrons_per_grey + read_noise_grey * read_noise_grey);
      raw.at<std::uint8_t>(y, x) = cv::saturate_cast<std::uint8_t>(s + sigma * normal(rng));
    }
  out.jpeg_quality = static_cast<int>(uniform(55, 90));
  cv::imencode(".jpg", raw, out.jpeg, {cv::IMWRITE_JPEG_QUALITY, out.jpeg_quality});
  out.image = cv::imdecode(out.jpeg, cv::IMREAD_GRAYSCALE);
  return out;
}

std::vector<RealisticImage> realistic_marker_set(int count, std::uint64_t first_seed) {
  std::vector<RealisticImage> set;
  for (int i = 0; i < count; ++i) set.push_back(realistic_marker_image(first_seed + static_cast<std::uint64_t>(i)));
  return set;
}

RealisticScore& RealisticScore::operator+=(const RealisticScore& o) {
  whole_dots += o.whole_dots, whole_found += o.whole_found, detections += o.detections, paired += o.paired;
  merged_dots += o.merged_dots, merged_found += o.merged_found;
  cut_dots += o.cut_dots, cut_detected += o.cut_detected, extra_on_a_dot += o.extra_on_a_dot;
  return *this;
}

std::string RealisticScore::str() const {
  std::ostringstream o;
  o << "recall " << recall() << " (" << whole_found << "/" << whole_dots << " whole dots within 2 px; merged " << merged_found << "/"
    << merged_dots << "), precision "
    << precision() << " (" << paired << "/" << detections << "), cut dots detected " << cut_detected << "/"
    << cut_dots << ", extra detections on a dot " << extra_on_a_dot;
  return o.str();
}

RealisticScore score_realistic(const std::vector<Eigen::Vector2d>& detected_px, const RealisticImage& truth,
                               double recall_margin_px) {
  constexpr double kFoundWithinPx = 2.0;
  struct Pair {
    double distance;
    std::size_t detection, dot;
  };
  std::vector<Pair> pairs;
  std::vector<bool> on_a_dot(detected_px.size(), false);
  for (std::size_t i = 0; i < detected_px.size(); ++i)
    for (std::size_t k = 0; k < truth.dots.size(); ++k) {
      const double d = (detected_px[i] - truth.dots[k].centre_px).norm();
      if (d > truth.dots[k].semi_major_px) continue;
      pairs.push_back({d, i, k});
      on_a_dot[i] = true;
    }
  std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) { return a.distance < b.distance; });
  std::vector<bool> detection_taken(detected_px.size(), false), dot_taken(truth.dots.size(), false);
  RealisticScore s;
  s.detections = static_cast<int>(detected_px.size());
  for (const Pair& p : pairs) {
    if (detection_taken[p.detection] || dot_taken[p.dot]) continue;
    detection_taken[p.detection] = dot_taken[p.dot] = true;
    ++s.paired;
    const TrueDot& dot = truth.dots[p.dot];
    if (dot.cut) ++s.cut_detected;
    else if (p.distance <= kFoundWithinPx && dot.border_gap_px >= recall_margin_px)
      ++s.whole_found, s.merged_found += dot.merged;
  }
  for (const TrueDot& d : truth.dots) {
    if (d.cut) ++s.cut_dots;
    if (d.cut || d.border_gap_px < recall_margin_px) continue;
    ++s.whole_dots;
    s.merged_dots += d.merged;
  }
  for (std::size_t i = 0; i < detected_px.size(); ++i) s.extra_on_a_dot += on_a_dot[i] && !detection_taken[i];
  return s;
}

RealisticScore score_realistic(const std::vector<Marker>& detected, const RealisticImage& truth,
                               double recall_margin_px) {
  std::vector<Eigen::Vector2d> px;
  px.reserve(detected.size());
  for (const Marker& m : detected) px.push_back(m.centre_px);
  return score_realistic(px, truth, recall_margin_px);
}

}  // namespace touchcloud::test
