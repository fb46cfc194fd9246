#include "touchcloud/simulation/render/marker_renderer.hpp"

#include <algorithm>
#include <cmath>

namespace touchcloud::simulation {

namespace {

// The share of a unit pixel on the inner side of a straight edge whose unit
// normal is (nx, ny) and which passes `inside` px beyond the pixel's centre:
// the distribution of n . x over the square is a trapezoid, this its CDF.
// Exact for a straight rim; the caller allows for the rim's curvature.
double square_coverage(double nx, double ny, double inside) {
  const double a = std::max(nx, ny), b = std::min(nx, ny);
  const double half_sum = 0.5 * (a + b), half_diff = 0.5 * (a - b);
  if (inside <= -half_sum) return 0.0;
  if (inside >= half_sum) return 1.0;
  if (inside < -half_diff) return (inside + half_sum) * (inside + half_sum) / (2 * a * b);
  if (inside <= half_diff) return 0.5 + inside / a;
  return 1.0 - (half_sum - inside) * (half_sum - inside) / (2 * a * b);
}

}  // namespace

MarkerRenderer::MarkerRenderer(int width_px, int height_px, const RenderStyle& style)
    : background_(height_px, width_px, CV_8UC1), marker_grey_(style.marker_grey) {
  const double cx = 0.5 * (width_px - 1), cy = 0.5 * (height_px - 1);
  const double corner2 = cx * cx + cy * cy;
  for (int y = 0; y < height_px; ++y) {
    auto* row = background_.ptr<std::uint8_t>(y);
    for (int x = 0; x < width_px; ++x) {
      const double r2 = ((x - cx) * (x - cx) + (y - cy) * (y - cy)) / corner2;
      // cos^4-like fall-off, smooth and flat at the centre.
      const double light = (1.0 - style.vignetting * r2 * (2.0 - r2)) * (1.0 + style.gradient * (x - cx) / (2 * cx));
      row[x] = cv::saturate_cast<std::uint8_t>(style.background_grey * light);
    }
  }
}

cv::Mat MarkerRenderer::render(const std::vector<MarkerDot>& dots) const {
  cv::Mat image = background_.clone();
  const int w = image.cols, h = image.rows;
  for (const auto& dot : dots) {
    const double r = dot.radius_px;
    if (!(r > 0)) continue;
    const double cx = dot.centre_px.x(), cy = dot.centre_px.y();
    const int x0 = std::max(0, static_cast<int>(std::floor(cx - r - 0.5))),
              x1 = std::min(w - 1, static_cast<int>(std::ceil(cx + r + 0.5)));
    const int y0 = std::max(0, static_cast<int>(std::floor(cy - r - 0.5))),
              y1 = std::min(h - 1, static_cast<int>(std::ceil(cy + r + 0.5)));
    // Across a pixel the rim bends away from its tangent by x^2 / (2r); the
    // pixel's mean x^2 along any direction is 1/12.
    const double sagitta = 1.0 / (24.0 * r);
    // A pixel's centre within sqrt(2)/2 of the rim is partly covered.
    const double outer2 = (r + M_SQRT1_2) * (r + M_SQRT1_2);
    const double inner2 = r > M_SQRT1_2 ? (r - M_SQRT1_2) * (r - M_SQRT1_2) : -1.0;
    for (int y = y0; y <= y1; ++y) {
      auto* row = image.ptr<std::uint8_t>(y);
      const auto* bg = background_.ptr<std::uint8_t>(y);
      const double dy2 = (y - cy) * (y - cy);
      for (int x = x0; x <= x1; ++x) {
        const double d2 = (x - cx) * (x - cx) + dy2;
        if (d2 >= outer2) continue;
        double coverage = 1.0;
        if (d2 > inner2) {
          const double d = std::sqrt(d2);
          coverage = d > 0 ? square_coverage(std::abs(x - cx) / d, std::abs(y - cy) / d, r - d - sagitta) : 1.0;
        }
        const double value = bg[x] - coverage * (bg[x] - marker_grey_);
        row[x] = std::min(row[x], static_cast<std::uint8_t>(value + 0.5));
      }
    }
  }
  return image;
}

}  // namespace touchcloud::simulation
