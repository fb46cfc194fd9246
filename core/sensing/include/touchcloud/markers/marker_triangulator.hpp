// Marker positions from matched pixel pairs, frame after frame, by
// refractive stereo ray tracing (RSRT): each pixel's ray is refracted at the
// air/acrylic and acrylic/silicone faces, and the two silicone rays are
// intersected (cross-product midpoint, their gap as the point's quality).
// With `refraction` off, straight camera rays are intersected instead: the
// pinhole model, millimetres off on this sensor, kept for comparison.
//
// A marker's reference (no-contact) position is where it was first
// triangulated: the first frame must be taken without contact.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Geometry>

#include "touchcloud/optics/stereo_rig.hpp"
#include "touchcloud/types/marker_set.hpp"
#include "touchcloud/types/tactile_cloud.hpp"

namespace touchcloud::markers {

struct TriangulationCounts {
  // Pairs refused, indexed by optics::TriangulationStatus (Ok unused), then
  // one more for "gap above max_gap_mm".
  std::array<std::size_t, 6> refused{};
  std::size_t frames = 0, points = 0;
  double gap_sum_mm = 0, gap_max_mm = 0;
};

class MarkerTriangulator {
 public:
  MarkerTriangulator(optics::StereoRig rig, const Eigen::Isometry3d& sensor_from_left, bool refraction,
                     double max_gap_mm);

  // The frame's tactile cloud (sensor frame), points in the order of the
  // frame's matches; pose and timestamp are left to the caller. InputError
  // when a match has no id or points at no marker.
  TactileCloud triangulate(const MarkerSet& frame);

  const TriangulationCounts& counts() const { return counts_; }

 private:
  optics::StereoRig rig_;
  Eigen::Isometry3d sensor_from_left_;
  bool refraction_;
  double max_gap_mm_;
  std::vector<Eigen::Vector3d> reference_mm_;  // by marker id
  std::vector<char> has_reference_;
  TriangulationCounts counts_;
};

}  // namespace touchcloud::markers
