#include "touchcloud/simulation/gel/gel_contact.hpp"

#include <algorithm>
#include <cmath>

namespace touchcloud::simulation {

void press_gel(const std::vector<Eigen::Vector3d>& rest_sensor_mm, const Eigen::Isometry3d& base_from_sensor,
               const ObjectSurface& object, const GelContactOptions& options, GelState& state) {
  const std::size_t n = rest_sensor_mm.size();
  state.markers_sensor_mm = rest_sensor_mm;
  state.markers_base_mm.resize(n);
  state.overlapping.assign(n, 0);
  state.markers_overlapping = 0;
  state.max_overlap_mm = 0;
  std::vector<double> rise(n, 0.0);
  std::vector<std::size_t> in_contact;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d p = base_from_sensor * rest_sensor_mm[i];
    state.markers_base_mm[i] = p;
    const double overlap = object.overlap_mm(p.head<2>(), p.z());
    if (overlap > 0) {
      ++state.markers_overlapping;
      state.overlapping[i] = 1;
      state.max_overlap_mm = std::max(state.max_overlap_mm, overlap);
      rise[i] = overlap;
      in_contact.push_back(i);
    }
  }
  if (!options.contact || in_contact.empty()) return;

  if (options.elastic_spread) {
    const double inv_two_sigma2 = 1.0 / (2.0 * options.spread_sigma_mm * options.spread_sigma_mm);
    // Beyond 6 sigma the fall-off is below 2e-8: nothing moves there.
    const double cutoff2 = 36.0 * options.spread_sigma_mm * options.spread_sigma_mm;
    for (std::size_t k = 0; k < n; ++k) {
      if (rise[k] > 0) continue;
      double lift = 0;
      for (std::size_t i : in_contact) {
        const double d2 = (rest_sensor_mm[k] - rest_sensor_mm[i]).squaredNorm();
        if (d2 < cutoff2) lift = std::max(lift, rise[i] * std::exp(-d2 * inv_two_sigma2));
      }
      rise[k] = lift;
    }
  }

  // Rising is +z in the base frame; in the sensor frame it is whatever that maps to.
  const Eigen::Vector3d up_sensor = base_from_sensor.linear().transpose() * Eigen::Vector3d::UnitZ();
  for (std::size_t i = 0; i < n; ++i) {
    if (!(rise[i] > 0)) continue;
    state.markers_base_mm[i].z() += rise[i];
    state.markers_sensor_mm[i] += rise[i] * up_sensor;
  }
}

}  // namespace touchcloud::simulation
