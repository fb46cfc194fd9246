#include "touchcloud/markers/stereo_matcher.hpp"

#include <cmath>
#include <limits>

#include "markers/pixel_index.hpp"

namespace touchcloud::markers {

RestingGelMatcher::RestingGelMatcher(optics::StereoRig rig, const Eigen::Isometry3d& left_from_sensor,
                                     double gel_radius_mm)
    : rig_(std::move(rig)), sensor_from_left_(left_from_sensor.inverse()), gel_radius_mm_(gel_radius_mm) {}

bool RestingGelMatcher::predict_right(const Eigen::Vector2d& left_px, Eigen::Vector2d& right_px) const {
  const auto ray = optics::back_project_refracted(rig_, optics::StereoSide::Left, left_px);
  if (ray.status != optics::TraceStatus::Ok) return false;
  // The ray starts on the gel's flat base (inside the sphere) and leaves the
  // hemisphere once: the positive root of |o + s d|^2 = R^2 (sensor frame).
  const Eigen::Vector3d o = sensor_from_left_ * ray.origin_mm;
  const Eigen::Vector3d d = sensor_from_left_.linear() * ray.direction;
  const double b = o.dot(d), c = o.squaredNorm() - gel_radius_mm_ * gel_radius_mm_;
  const double discriminant = b * b - c;
  if (!(c < 0) || !(discriminant > 0)) return false;  // the ray enters beside the gel
  const double s = -b + std::sqrt(discriminant);
  const Eigen::Vector3d marker_left = ray.origin_mm + s * ray.direction;
  const auto pixel = optics::project_refracted(rig_, optics::StereoSide::Right, marker_left);
  if (pixel.status != optics::TraceStatus::Ok) return false;
  right_px = pixel.pixel_px;
  return true;
}

std::vector<MarkerMatch> RestingGelMatcher::match(const std::vector<Marker>& left, const std::vector<Marker>& right,
                                                  double gate_px) const {
  const PixelIndex right_index(right);
  std::vector<int> claimed_by(right.size(), -1);
  std::vector<double> claim_px(right.size(), std::numeric_limits<double>::infinity());
  for (std::size_t l = 0; l < left.size(); ++l) {
    Eigen::Vector2d predicted;
    if (!predict_right(left[l].centre_px, predicted)) continue;
    const Nearest n = right_index.nearest(predicted, gate_px);
    if (n.index < 0 || !(n.distance_px < claim_px[n.index])) continue;
    claimed_by[n.index] = static_cast<int>(l);
    claim_px[n.index] = n.distance_px;
  }
  std::vector<MarkerMatch> matches;
  for (std::size_t r = 0; r < right.size(); ++r)
    if (claimed_by[r] >= 0) matches.push_back({claimed_by[r], static_cast<int>(r), -1});
  return matches;
}

}  // namespace touchcloud::markers
