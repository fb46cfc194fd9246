#include "touchcloud/simulation/objects/analytic_surfaces.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace touchcloud::simulation {

namespace {

double smoothstep(double edge0, double edge1, double x) {
  const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

double wave_height(double x, double y) {
  const double waves_on = smoothstep(-90, -65, x);  // flat below x = -90
  const double long_wave = 7.0 * std::sin(2 * M_PI * x / 100);
  // |sin| folds the 40 mm wave into sharp crests.
  const double crested_wave = 2.0 * (1 - 2 * std::abs(std::sin(M_PI * (x + 10) / 40)));
  const double ripples = 0.8 * smoothstep(35, 50, x) * std::sin(2 * M_PI * x / 6);
  const double arch = 1.5 * std::cos(M_PI * y / 50);
  return 14.0 + waves_on * (long_wave + crested_wave) + ripples + arch;
}

// A cone of height h and base radius r with a sharpened tip (exponent > 1).
double pointed(double dx, double dy, double h, double r, double sharpness) {
  const double d = std::hypot(dx, dy);
  return d >= r ? 0.0 : h * std::pow(1 - d / r, sharpness);
}

// A pyramid of height h over the triangle abc, its peak above `peak` (inside
// abc): sharp ridges run from the peak to the corners.
double pyramid(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
               const Eigen::Vector2d& peak, double h) {
  const std::array<std::pair<Eigen::Vector2d, Eigen::Vector2d>, 3> edges{{{a, b}, {b, c}, {c, a}}};
  const auto inside_distance = [](const Eigen::Vector2d& q, const Eigen::Vector2d& e0, const Eigen::Vector2d& e1,
                                  const Eigen::Vector2d& ref) {
    const Eigen::Vector2d n = Eigen::Vector2d(e1.y() - e0.y(), e0.x() - e1.x()).normalized();
    const double d = n.dot(q - e0);
    return n.dot(ref - e0) < 0 ? -d : d;  // positive on the side of `ref`
  };
  double level = 1.0;
  for (const auto& [e0, e1] : edges) level = std::min(level, inside_distance(p, e0, e1, peak) / inside_distance(peak, e0, e1, peak));
  return level > 0 ? h * level : 0.0;
}

// An almond-shaped hollow (Gaussian), its long axis turned by `angle_rad`.
double hollow(double dx, double dy, double depth, double sigma_long, double sigma_short, double angle_rad) {
  const double u = std::cos(angle_rad) * dx + std::sin(angle_rad) * dy;
  const double v = -std::sin(angle_rad) * dx + std::cos(angle_rad) * dy;
  return -depth * std::exp(-0.5 * (u * u / (sigma_long * sigma_long) + v * v / (sigma_short * sigma_short)));
}

// The snout: a ridge from the face (y = 5) to the nose (y = -46), narrowing
// and rising towards its rounded end.
double snout(double x, double y) {
  constexpr double y_face = 5.0, y_nose = -46.0;
  if (y < y_nose) {
    const double r2 = (x * x + (y - y_nose) * (y - y_nose)) / 36.0;
    return r2 < 1 ? 12.0 * (1 - r2) : 0.0;
  }
  const double t = std::clamp((y_face - y) / (y_face - y_nose), 0.0, 1.0);
  const double half_width = 20.0 - 14.0 * t, height = 10.0 + 2.0 * t;
  const double across = 1 - (x / half_width) * (x / half_width);
  const double fade = y > y_face ? 1.0 - smoothstep(y_face, y_face + 12.0, y) : 1.0;
  return across > 0 ? height * across * fade : 0.0;
}

double fox_height(double x, double y) {
  constexpr double base = 4.0;
  const Eigen::Vector2d p(x, y);
  const double rx = x / 46, ry = (y - 8) / 34;
  const double face = std::max(0.0, 14.0 * (1 - rx * rx - ry * ry));
  const double eyes = hollow(x - 17, y - 14, 6.0, 6.0, 3.0, 0.45) + hollow(x + 17, y - 14, 6.0, 6.0, 3.0, -0.45);
  const double nose = pointed(x, y + 46, 6.0, 5.0, 1.5);
  const double ears = pyramid(p, {-50, 24}, {-16, 32}, {-42, 58}, {-38, 40}, 20.0) +
                      pyramid(p, {50, 24}, {42, 58}, {16, 32}, {38, 40}, 20.0);
  return base + std::max(0.0, face + snout(x, y) + nose + eyes) + ears;
}

}  // namespace

const AnalyticSurface& wave_surface() {
  static const AnalyticSurface s{"wave_surface", Eigen::AlignedBox2d(Eigen::Vector2d(-100, -25), Eigen::Vector2d(100, 25)),
                                 &wave_height};
  return s;
}

const AnalyticSurface& fox_mask() {
  static const AnalyticSurface s{"fox_mask", Eigen::AlignedBox2d(Eigen::Vector2d(-60, -60), Eigen::Vector2d(60, 60)),
                                 &fox_height};
  return s;
}

}  // namespace touchcloud::simulation
