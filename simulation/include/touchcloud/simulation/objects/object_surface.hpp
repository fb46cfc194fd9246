// The object on the table as the gel meets it from above: the height of its
// upper surface over the table, in the base frame (mm).
#pragma once

#include <memory>

#include <Eigen/Core>

#include "touchcloud/simulation/scene/scene.hpp"

namespace touchcloud::simulation {

class ObjectSurface {
 public:
  virtual ~ObjectSurface() = default;
  // z of the upper surface at (x, y): the object's top where it is, the table
  // (z = 0) around it. Never below 0.
  virtual double height_mm(const Eigen::Vector2d& xy_mm) const = 0;
  // The highest surface point within `radius_mm` of `centre_mm`: exact or
  // above for meshes (a cell-wise bound), sampled for analytic surfaces (see
  // there); used to start touches clear of the object.
  virtual double max_height_mm(const Eigen::Vector2d& centre_mm, double radius_mm) const = 0;
  // How far a point at (x, y, z) lies below the surface: height_mm(xy) - z
  // whenever that is positive, otherwise some value <= 0. The gel's contact
  // test, for every marker in every frame; a surface may answer it without
  // the height where the point is clearly above.
  virtual double overlap_mm(const Eigen::Vector2d& xy_mm, double z_mm) const { return height_mm(xy_mm) - z_mm; }
};

// Builds the scene's object. A mesh that cannot be read, holds no triangles
// or has no upward-facing area throws InputError naming `object.mesh`.
std::unique_ptr<ObjectSurface> make_object_surface(const ObjectSpec& object);

}  // namespace touchcloud::simulation
