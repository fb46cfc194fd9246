// Where the markers are when the gel meets the object. The sensor faces
// down; a marker whose position in the base frame lies below the object's
// upper surface overlaps the object.
//
//   contact         an overlapping marker rises vertically onto the surface
//                   (the gel conforms where it overlaps).
//   elastic_spread  a marker out of contact rises by max_i u_i exp(-d_i^2 / (2 sigma^2)):
//                   u_i the rise of contact marker i, d_i < 6 sigma their distance at rest.
//                   Never more than the contact itself, never into the object.
//
// Without `contact` the markers stay at rest, whatever the overlap.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

#include "touchcloud/simulation/objects/object_surface.hpp"

namespace touchcloud::simulation {

struct GelContactOptions {
  bool contact = false;
  bool elastic_spread = false;
  double spread_sigma_mm = 3.0;
};

struct GelState {
  std::vector<Eigen::Vector3d> markers_sensor_mm;  // same order as the rest layout
  std::vector<Eigen::Vector3d> markers_base_mm;
  std::vector<std::uint8_t> overlapping;  // 1 where the rest marker lies below the object's surface
  std::size_t markers_overlapping = 0;  // markers of the rest gel below the surface
  double max_overlap_mm = 0;            // deepest of them
};

// `rest_sensor_mm`: the markers at rest in the sensor frame; `base_from_sensor`:
// the sensor's true pose.
void press_gel(const std::vector<Eigen::Vector3d>& rest_sensor_mm, const Eigen::Isometry3d& base_from_sensor,
               const ObjectSurface& object, const GelContactOptions& options, GelState& state);

}  // namespace touchcloud::simulation
