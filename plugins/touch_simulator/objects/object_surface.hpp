// The object on the table as the gel meets it from above: the height of its
// upper surface over the table, in the base frame (mm).
#pragma once

#include <memory>

#include <Eigen/Core>

#include "scene/scene.hpp"

namespace touchcloud::sim {

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
};

// Builds the scene's object. A mesh that cannot be read, holds no triangles
// or has no upward-facing area throws InputError naming `object.mesh`.
std::unique_ptr<ObjectSurface> make_object_surface(const ObjectSpec& object);

}  // namespace touchcloud::sim
