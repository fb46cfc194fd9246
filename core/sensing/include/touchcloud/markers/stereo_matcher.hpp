// Pairs the left and right markers of the no-contact reference frame through
// the sensor model: a left marker's ray, refracted into the silicone, meets
// the resting gel (a hemisphere on the plate) at the marker; projected into
// the right camera, that point predicts where the right view shows it. The
// nearest right marker within a gate is its partner. Needs no epipolar
// geometry, which refraction bends into curves.
#pragma once

#include <vector>

#include <Eigen/Geometry>

#include "touchcloud/optics/stereo_rig.hpp"
#include "touchcloud/types/marker_set.hpp"

namespace touchcloud::markers {

class RestingGelMatcher {
 public:
  RestingGelMatcher(optics::StereoRig rig, const Eigen::Isometry3d& left_from_sensor, double gel_radius_mm);

  // Where the right camera sees the resting-gel point behind `left_px`;
  // false when the ray misses the gel or the right camera does not see it.
  bool predict_right(const Eigen::Vector2d& left_px, Eigen::Vector2d& right_px) const;

  // One match per pair (ids unset); a right marker claimed by several left
  // ones goes to the nearest prediction.
  std::vector<MarkerMatch> match(const std::vector<Marker>& left, const std::vector<Marker>& right,
                                 double gate_px) const;

 private:
  optics::StereoRig rig_;
  Eigen::Isometry3d sensor_from_left_;
  double gel_radius_mm_;
};

}  // namespace touchcloud::markers
