#include "salient_points.hpp"

#include <algorithm>

#include "touchcloud/error.hpp"

namespace touchcloud::saliency {

std::vector<std::size_t> salient_markers(const std::vector<double>& displacement_mm, double alpha,
                                         SalientSelection selection) {
  std::vector<std::size_t> kept;
  if (displacement_mm.empty()) return kept;
  const auto deepest = std::max_element(displacement_mm.begin(), displacement_mm.end());
  const double max_d = *deepest;
  if (!(max_d > 0)) return kept;
  if (selection == SalientSelection::Deepest) return {static_cast<std::size_t>(deepest - displacement_mm.begin())};
  const double threshold = alpha * max_d;
  for (std::size_t j = 0; j < displacement_mm.size(); ++j)
    if (displacement_mm[j] > threshold) kept.push_back(j);
  return kept;
}

CloudPtr salient_cloud(const TactileCloud& tactile, const std::vector<std::size_t>& indices, Frame frame) {
  auto out = std::make_shared<PointCloud>();
  out->reserve(indices.size());
  const Eigen::Isometry3d& base_from_sensor = tactile.pose.base_from_sensor;
  for (std::size_t j : indices) {
    const auto& p = tactile.points->at(j);
    Eigen::Vector3d q(p.x, p.y, p.z);
    if (frame == Frame::Base) q = base_from_sensor * q;
    else if (frame != Frame::Sensor) throw InputError("salient clouds are given in the sensor or base frame");
    out->push_back(pcl::PointXYZ(static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(q.z())));
  }
  return out;
}

}  // namespace touchcloud::saliency
