#include "touchcloud/planning/side_choice.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include <Eigen/Geometry>

#include "touchcloud/error.hpp"

namespace touchcloud::planning {

std::vector<SideCandidate> side_candidates(const ImplicitModel& model, const std::vector<Eigen::Vector3d>& surface_mm,
                                           const SideChoiceOptions& options, std::uint64_t seed) {
  if (surface_mm.empty()) throw InputError("no predicted surface points to choose a touch among");
  // A seeded draw without repeats: the first `count` of a shuffle.
  std::vector<std::size_t> order(surface_mm.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::mt19937_64 rng(seed);
  const std::size_t count = std::min(order.size(), static_cast<std::size_t>(std::max(options.candidates, 1)));
  for (std::size_t i = 0; i < count; ++i)
    std::swap(order[i], order[i + std::uniform_int_distribution<std::size_t>(0, order.size() - 1 - i)(rng)]);
  const auto n = static_cast<Eigen::Index>(count);
  Eigen::MatrixX3d points(n, 3), probes(6 * n, 3);
  const double h = options.gradient_step_mm;
  for (Eigen::Index i = 0; i < n; ++i) {
    points.row(i) = surface_mm[order[static_cast<std::size_t>(i)]].transpose();
    for (int axis = 0; axis < 3; ++axis)
      for (int side = 0; side < 2; ++side) {
        Eigen::RowVector3d p = points.row(i);
        p(axis) += side == 0 ? h : -h;
        probes.row(6 * i + 2 * axis + side) = p;
      }
  }
  const Eigen::VectorXd f = model.mean(probes);
  const Eigen::VectorXd variance = model.variance(points);
  std::vector<SideCandidate> out;
  out.reserve(count);
  for (Eigen::Index i = 0; i < n; ++i) {
    Eigen::Vector3d g;
    for (int axis = 0; axis < 3; ++axis) g(axis) = f(6 * i + 2 * axis) - f(6 * i + 2 * axis + 1);
    if (!(g.norm() > 0) || !g.allFinite()) continue;
    SideCandidate c;
    c.point_mm = points.row(i).transpose();
    c.outward = g.normalized();
    c.variance_mm2 = variance(i);
    out.push_back(c);
  }
  const double r2 = options.footprint_radius_mm * options.footprint_radius_mm;
  for (SideCandidate& c : out)
    for (const SideCandidate& o : out) {
      const Eigen::Vector3d d = o.point_mm - c.point_mm;
      const double along = d.dot(c.outward);
      if (std::abs(along) <= options.depth_mm && d.squaredNorm() - along * along <= r2)
        c.footprint_variance_mm2 += o.variance_mm2;
    }
  std::stable_sort(out.begin(), out.end(), [](const SideCandidate& a, const SideCandidate& b) {
    return a.footprint_variance_mm2 > b.footprint_variance_mm2;
  });
  return out;
}

std::vector<Eigen::Vector3d> press_directions(const Eigen::Vector3d& outward, const std::vector<double>& oblique_deg) {
  std::vector<Eigen::Vector3d> out{-outward};  // against the normal: -outward itself, not normalised again
  const Eigen::Vector3d normal = -outward.normalized(), down(0, 0, -1);
  const Eigen::Vector3d axis = normal.cross(down);
  if (axis.norm() < 1e-9) return out;  // straight down or straight up: no way to turn towards down
  const double to_down = std::atan2(axis.norm(), normal.dot(down));
  for (const double deg : oblique_deg) {
    const double angle = std::min(deg * M_PI / 180.0, to_down);
    out.push_back((Eigen::AngleAxisd(angle, axis.normalized()) * normal).normalized());
  }
  return out;
}

std::vector<Eigen::Vector3d> start_directions(int count, double tilt_deg) {
  std::vector<Eigen::Vector3d> out{Eigen::Vector3d(0, 0, -1)};
  const double tilt = tilt_deg * M_PI / 180.0;
  for (int k = 0; k + 1 < count; ++k) {
    const double azimuth = 2 * M_PI * k / (count - 1);
    // Coming from azimuth's side, heading in and down.
    out.emplace_back(-std::sin(tilt) * std::cos(azimuth), -std::sin(tilt) * std::sin(azimuth), -std::cos(tilt));
  }
  return out;
}

}  // namespace touchcloud::planning
