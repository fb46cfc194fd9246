#include "dot_window.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <Eigen/Eigenvalues>

namespace touchcloud::imaging {

namespace {

constexpr int kKMeansIterations = 8;

// Contrast-weighted sums over pixels, with coordinates relative to an origin
// near the window's centre so that the sums stay exact in doubles.
struct WeightedSums {
  double w = 0, wx = 0, wy = 0, wxx = 0, wyy = 0, wxy = 0, peak = 0;

  void add(double weight, double dx, double dy) {
    w += weight, wx += weight * dx, wy += weight * dy;
    wxx += weight * dx * dx, wyy += weight * dy * dy, wxy += weight * dx * dy;
  }
  DotMoments moments(const Eigen::Vector2d& origin, bool clipped) const {
    DotMoments m;
    m.ink = w;
    m.peak_grey = peak;
    m.clipped = clipped;
    if (!(w > 0)) return m;
    const double mx = wx / w, my = wy / w;
    m.centre_px = origin + Eigen::Vector2d(mx, my);
    m.covariance_px2 << wxx / w - mx * mx, wxy / w - mx * my, wxy / w - mx * my, wyy / w - my * my;
    return m;
  }
};

// Whether a pixel counts for the blob: not part of another blob (past the
// threshold outside the blob's box).
struct PixelFilter {
  int threshold;
  cv::Rect box;
  bool row_in_box(int y) const { return y >= box.y && y < box.y + box.height; }
  bool keep(int contrast, int x, bool row_in_box) const {
    return contrast <= threshold || (row_in_box && x >= box.x && x < box.x + box.width);
  }
};

// The grey level on the window's rim (its sides inside the image), the local
// background: the mean, then the mean of the pixels within the threshold of it
// (a neighbouring dot may cross the rim).
int rim_grey(const cv::Mat& grey, const DotWindow& win, int sign, const PixelFilter& filter) {
  const cv::Rect& r = win.rect;
  const int x0 = r.x, x1 = r.x + r.width - 1, y0 = r.y, y1 = r.y + r.height - 1;
  auto mean = [&](int reference) {
    int sum = 0, count = 0;
    for (int y = y0; y <= y1; ++y) {
      const auto* g = grey.ptr<std::uint8_t>(y);
      const bool in_box = filter.row_in_box(y);
      auto add = [&](int x) {
        if (reference < 0 || filter.keep(sign * (g[x] - reference), x, in_box)) sum += g[x], ++count;
      };
      if ((y == y0 && !win.cut_top) || (y == y1 && !win.cut_bottom)) {
        for (int x = x0; x <= x1; ++x) add(x);
        continue;
      }
      if (!win.cut_left) add(x0);
      if (!win.cut_right && x1 != x0) add(x1);
    }
    return count > 0 ? (sum + count / 2) / count : -1;
  };
  const int first = mean(-1);
  const int second = first < 0 ? -1 : mean(first);
  if (second >= 0) return second;
  if (first >= 0) return first;
  // No rim inside the image: the window's brightest (dark dots) or darkest pixel.
  double lo = 0, hi = 0;
  cv::minMaxLoc(grey(r), &lo, &hi);
  return static_cast<int>(sign < 0 ? hi : lo);
}

}  // namespace

Eigen::Vector2d DotMoments::principal_variances_px2() const {
  const double mean = 0.5 * (covariance_px2(0, 0) + covariance_px2(1, 1));
  const double half_diff = 0.5 * (covariance_px2(0, 0) - covariance_px2(1, 1));
  const double radius = std::sqrt(half_diff * half_diff + covariance_px2(0, 1) * covariance_px2(0, 1));
  return {mean + radius, mean - radius};
}

Eigen::Vector2d DotMoments::major_axis() const {
  const double angle = 0.5 * std::atan2(2 * covariance_px2(0, 1), covariance_px2(0, 0) - covariance_px2(1, 1));
  return {std::cos(angle), std::sin(angle)};
}

double DotMoments::elongation() const {
  const Eigen::Vector2d v = principal_variances_px2();
  return v.y() > 0 ? std::sqrt(v.x() / v.y()) : INFINITY;
}

double DotMoments::dots_by_ink() const {
  const double minor = principal_variances_px2().y();
  return minor > 0 && peak_grey > 0 ? ink / (4 * M_PI * minor * peak_grey) : INFINITY;
}

DotWindow fit_window(const cv::Rect& wanted, cv::Size image) {
  DotWindow w;
  w.cut_left = wanted.x < 0;
  w.cut_top = wanted.y < 0;
  w.cut_right = wanted.x + wanted.width > image.width;
  w.cut_bottom = wanted.y + wanted.height > image.height;
  w.rect = wanted & cv::Rect(0, 0, image.width, image.height);
  return w;
}

DotMoments measure_dot(const cv::Mat& grey, bool dark, const DotWindow& win, const cv::Rect& blob_box,
                       const ContrastLevels& levels) {
  const cv::Rect& r = win.rect;
  const PixelFilter filter{levels.threshold_grey, blob_box};
  const int sign = dark ? -1 : 1;
  const int rim = rim_grey(grey, win, sign, filter);
  const int floor = static_cast<int>(std::lround(levels.weight_floor_grey));
  const int ox = r.x + r.width / 2, oy = r.y + r.height / 2;
  // Exact integer sums, coordinates relative to (ox, oy); a row's fit in 32 bits.
  std::int64_t w0 = 0, wx = 0, wy = 0, wxx = 0, wyy = 0, wxy = 0;
  int peak = 0;
  for (int y = r.y; y < r.y + r.height; ++y) {
    const auto* g = grey.ptr<std::uint8_t>(y);
    const bool in_box = filter.row_in_box(y);
    std::int32_t s0 = 0, sx = 0, sxx = 0;
    for (int x = r.x; x < r.x + r.width; ++x) {
      const int v = sign * (g[x] - rim);
      const bool keep = filter.keep(v, x, in_box);
      const int w = keep ? std::max(v - floor, 0) : 0;
      peak = std::max(peak, keep ? v : 0);
      const int dx = x - ox;
      s0 += w, sx += w * dx, sxx += w * dx * dx;
    }
    const std::int64_t dy = y - oy;
    w0 += s0, wx += sx, wxx += sxx, wy += s0 * dy, wyy += s0 * dy * dy, wxy += sx * dy;
  }
  WeightedSums s;
  s.w = static_cast<double>(w0), s.wx = static_cast<double>(wx), s.wy = static_cast<double>(wy);
  s.wxx = static_cast<double>(wxx), s.wyy = static_cast<double>(wyy), s.wxy = static_cast<double>(wxy);
  s.peak = peak;
  return s.moments(Eigen::Vector2d(ox, oy), win.clipped());
}

std::vector<DotMoments> split_clump(const cv::Mat& grey, bool dark, const DotWindow& win, const cv::Rect& blob_box,
                                    const ContrastLevels& levels, const DotMoments& whole, int dots) {
  const PixelFilter filter{levels.threshold_grey, blob_box};
  const int sign = dark ? -1 : 1;
  const int rim = rim_grey(grey, win, sign, filter);
  const int floor = static_cast<int>(std::lround(levels.weight_floor_grey));
  const cv::Rect& r = win.rect;
  struct Pixel {
    double x, y, w;
  };
  std::vector<Pixel> pixels;
  pixels.reserve(static_cast<std::size_t>(r.area()));
  for (int y = r.y; y < r.y + r.height; ++y) {
    const auto* g = grey.ptr<std::uint8_t>(y);
    const bool in_box = filter.row_in_box(y);
    for (int x = r.x; x < r.x + r.width; ++x) {
      const int v = sign * (g[x] - rim);
      if (filter.keep(v, x, in_box) && v > floor) pixels.push_back({double(x), double(y), double(v - floor)});
    }
  }

  // k dots a distance s apart along the long axis add s^2 (k^2 - 1) / 12 to
  // its variance.
  const Eigen::Vector2d variances = whole.principal_variances_px2();
  const double spacing = std::sqrt(std::max(0.0, 12 * (variances.x() - variances.y()) / (dots * dots - 1)));
  std::vector<Eigen::Vector2d> seeds;
  for (int i = 0; i < dots; ++i) seeds.push_back(whole.centre_px + whole.major_axis() * spacing * (i - 0.5 * (dots - 1)));

  std::vector<int> owner(pixels.size(), 0);
  auto assign = [&] {
    for (std::size_t p = 0; p < pixels.size(); ++p) {
      double best = INFINITY;
      for (int k = 0; k < dots; ++k) {
        const double d = (Eigen::Vector2d(pixels[p].x, pixels[p].y) - seeds[k]).squaredNorm();
        if (d < best) best = d, owner[p] = k;
      }
    }
  };
  // Lloyd's iterations on the dots' ink.
  for (int it = 0; it < kKMeansIterations; ++it) {
    assign();
    std::vector<Eigen::Vector3d> acc(dots, Eigen::Vector3d::Zero());
    for (std::size_t p = 0; p < pixels.size(); ++p)
      acc[owner[p]] += pixels[p].w * Eigen::Vector3d(pixels[p].x, pixels[p].y, 1);
    for (int k = 0; k < dots; ++k)
      if (acc[k].z() > 0) seeds[k] = acc[k].head<2>() / acc[k].z();
  }
  assign();
  std::vector<WeightedSums> sums(dots);
  for (std::size_t p = 0; p < pixels.size(); ++p) {
    const Eigen::Vector2d d = Eigen::Vector2d(pixels[p].x, pixels[p].y) - seeds[owner[p]];
    sums[owner[p]].add(pixels[p].w, d.x(), d.y());
    sums[owner[p]].peak = std::max(sums[owner[p]].peak, pixels[p].w + levels.weight_floor_grey);
  }
  std::vector<DotMoments> out;
  for (int k = 0; k < dots; ++k) out.push_back(sums[k].moments(seeds[k], win.clipped()));
  return out;
}

}  // namespace touchcloud::imaging
