#include "touchcloud/simulation/gel/gel_surface.hpp"

#include <algorithm>
#include <cmath>

namespace touchcloud::simulation {

GelSurface::GelSurface(double radius_mm, double grid_mm)
    : radius_(radius_mm), grid_(grid_mm), n_(2 * static_cast<int>(std::ceil(radius_mm / grid_mm)) + 1) {
  const int half = n_ / 2;
  for (int j = 0; j < n_; ++j)
    for (int i = 0; i < n_; ++i) {
      const double x = (i - half) * grid_, y = (j - half) * grid_;
      if (x * x + y * y >= radius_ * radius_) continue;
      rest_.emplace_back(x, y, sphere_height_mm(x, y));
      node_of_rest_.push_back(j * n_ + i);
    }
  rest();
}

void GelSurface::rest() {
  rise_.assign(static_cast<std::size_t>(n_) * n_, 0.0);
  contact_.assign(rise_.size(), 0);
  has_rise_ = false;
  risen_.setEmpty();
}

void GelSurface::press(const Eigen::Isometry3d& base_from_sensor, const ObjectSurface& object,
                       const GelContactOptions& options) {
  rest();
  GelState state;
  press_gel(rest_, base_from_sensor, object, options, state);
  const int half = n_ / 2;
  for (std::size_t k = 0; k < rest_.size(); ++k) {
    const int node = node_of_rest_[k];
    // The rise is along the sensor's -z (PressTarget::sensor_pose); the lateral
    // part, zero for that pose, is left out.
    const double rise = rest_[k].z() - state.markers_sensor_mm[k].z();
    contact_[node] = state.overlapping[k] && options.contact;
    if (!(rise > 0)) continue;
    rise_[node] = rise;
    has_rise_ = true;
    const Eigen::Vector2d xy((node % n_ - half) * grid_, (node / n_ - half) * grid_);
    risen_.extend(xy - Eigen::Vector2d::Constant(grid_));
    risen_.extend(xy + Eigen::Vector2d::Constant(grid_));
  }
}

double GelSurface::sphere_height_mm(double x_mm, double y_mm) const {
  const double h2 = radius_ * radius_ - x_mm * x_mm - y_mm * y_mm;
  return h2 > 0 ? std::sqrt(h2) : 0.0;
}

double GelSurface::rise_mm(double x_mm, double y_mm) const {
  if (!has_rise_ || !risen_.contains(Eigen::Vector2d(x_mm, y_mm))) return 0.0;
  const int half = n_ / 2;
  const double u = x_mm / grid_ + half, v = y_mm / grid_ + half;
  const int i = std::clamp(static_cast<int>(std::floor(u)), 0, n_ - 2), j = std::clamp(static_cast<int>(std::floor(v)), 0, n_ - 2);
  const double a = u - i, b = v - j;
  const double* r = &rise_[static_cast<std::size_t>(j) * n_ + i];
  return (1 - b) * ((1 - a) * r[0] + a * r[1]) + b * ((1 - a) * r[n_] + a * r[n_ + 1]);
}

double GelSurface::height_mm(double x_mm, double y_mm) const {
  return sphere_height_mm(x_mm, y_mm) - rise_mm(x_mm, y_mm);
}

bool GelSurface::in_contact(double x_mm, double y_mm) const {
  if (!has_rise_) return false;
  const int half = n_ / 2;
  const int i = static_cast<int>(std::lround(x_mm / grid_)) + half, j = static_cast<int>(std::lround(y_mm / grid_)) + half;
  if (i < 0 || j < 0 || i >= n_ || j >= n_) return false;
  return contact_[static_cast<std::size_t>(j) * n_ + i] != 0;
}

std::optional<Eigen::Vector3d> GelSurface::intersect(const Eigen::Vector3d& origin_mm,
                                                     const Eigen::Vector3d& direction) const {
  // Exit through the rest dome: |o + l d|^2 = R^2.
  const double b = origin_mm.dot(direction), c = origin_mm.squaredNorm() - radius_ * radius_;
  if (!(c < 0) || !(direction.z() > 0)) return std::nullopt;
  const double exit = -b + std::sqrt(b * b - c);
  const Eigen::Vector3d at_exit = origin_mm + exit * direction;
  // Untouched where the ray runs: the dome itself (exact).
  if (!has_rise_) return at_exit;
  Eigen::AlignedBox2d path(origin_mm.head<2>());
  path.extend(at_exit.head<2>());
  if (!path.intersects(risen_)) return at_exit;
  // March to the first point above the surface, then bisect.
  auto above = [&](double l) {
    const Eigen::Vector3d p = origin_mm + l * direction;
    return p.z() - height_mm(p.x(), p.y());
  };
  const double step = 0.5 * grid_;
  double lo = 0, hi = exit;
  for (double l = step; l < exit; l += step) {
    if (above(l) >= 0) {
      hi = l;
      break;
    }
    lo = l;
  }
  for (int k = 0; k < 50 && hi - lo > 1e-9; ++k) {
    const double mid = 0.5 * (lo + hi);
    (above(mid) >= 0 ? hi : lo) = mid;
  }
  return origin_mm + hi * direction;
}

}  // namespace touchcloud::simulation
