// The gel's outer surface, densely, for the colour pattern: the hemisphere at
// rest, and where it is pressed, lowered towards the plate by the rise that
// press_gel gives the nodes of a regular grid over the sensor's (x, y). The
// robot presses straight down (the sensor's z is the base's -z), so a point
// of the surface moves along the sensor's z only and keeps its (x, y): the
// pattern printed at (x, y) stays there, which is how it moves with the gel.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "touchcloud/simulation/gel/gel_contact.hpp"
#include "touchcloud/simulation/objects/object_surface.hpp"

namespace touchcloud::simulation {

class GelSurface {
 public:
  // A grid of `grid_mm` spacing over the gel's base disc (radius in mm).
  GelSurface(double radius_mm, double grid_mm);

  // The surface under the sensor's true pose `base_from_sensor`; the rest
  // surface when `options.contact` is off.
  void press(const Eigen::Isometry3d& base_from_sensor, const ObjectSurface& object, const GelContactOptions& options);
  void rest();

  double radius_mm() const { return radius_; }
  // z of the surface above (x, y) in the sensor frame (0 outside the disc).
  double height_mm(double x_mm, double y_mm) const;
  // Whether the gel at (x, y) touches the object (its rest point overlaps it).
  bool in_contact(double x_mm, double y_mm) const;
  bool pressed() const { return has_rise_; }

  // Where a ray in the silicone (sensor frame, starting on the gel-side face
  // of the plate, heading into the gel) first meets the surface; nothing
  // when it starts outside the gel's base.
  std::optional<Eigen::Vector3d> intersect(const Eigen::Vector3d& origin_mm, const Eigen::Vector3d& direction) const;

 private:
  double rise_mm(double x_mm, double y_mm) const;  // bilinear
  double sphere_height_mm(double x_mm, double y_mm) const;

  double radius_, grid_;
  int n_;                                // nodes per side
  std::vector<Eigen::Vector3d> rest_;    // nodes inside the disc, on the dome
  std::vector<int> node_of_rest_;        // their index in the n x n grid
  std::vector<double> rise_;             // n x n, mm towards the plate
  std::vector<std::uint8_t> contact_;    // n x n
  bool has_rise_ = false;
  Eigen::AlignedBox2d risen_;            // (x, y) box of the nodes that rose, grown by a node
};

}  // namespace touchcloud::simulation
