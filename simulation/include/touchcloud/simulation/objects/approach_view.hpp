// The object and the table as a touch from any side meets them: the surface
// seen along the -z of a press frame (the approach frame of a touch target,
// or the base frame turned by a turntable), as the height field the vertical
// press works on. A mesh object is moved into the press frame and read by
// MeshSurface (exact to the mesh); the table is the plane z = 0 of the
// object's frame, where it faces the press (seen from above the horizon);
// where neither lies, a floor 1 mm below the object's lowest point in the
// press frame stops the gel (floor_mm: a touch that reaches it missed both).
#pragma once

#include <memory>
#include <optional>

#include <Eigen/Geometry>

#include "touchcloud/scoring/triangle_mesh.hpp"
#include "touchcloud/simulation/objects/mesh_surface.hpp"

namespace touchcloud::simulation {

class ApproachView final : public ObjectSurface {
 public:
  // `object_mm`: the placed object's mesh in the object's frame (table at
  // z = 0); `press_from_object`: that frame in the press frame.
  ApproachView(const scoring::TriangleMesh& object_mm, const Eigen::Isometry3d& press_from_object);
  // The same for questions within `within_mm` of the press's axis, (x, y) =
  // (0, 0), alone (a reach check: the gel's disc): only the triangles whose
  // footprint comes that near are indexed. Inside that disc every height is
  // the full view's, bit for bit; the floor and the table are the same
  // everywhere.
  ApproachView(const scoring::TriangleMesh& object_mm, const Eigen::Isometry3d& press_from_object, double within_mm);

  // Heights in the press frame: negative where the object lies below its origin.
  double height_mm(const Eigen::Vector2d& xy_mm) const override;
  double max_height_mm(const Eigen::Vector2d& centre_mm, double radius_mm) const override;
  double overlap_mm(const Eigen::Vector2d& xy_mm, double z_mm) const override;
  double floor_mm() const { return -lift_mm_; }
  // The table's height at (x, y) in the press frame; nothing where the press
  // does not face it (a touch along or below the horizon).
  std::optional<double> table_height_mm(const Eigen::Vector2d& xy_mm) const;

 private:
  // Lifted by lift_mm_ so that every vertex lies above z = 0; null where a
  // view within a radius has no triangle facing the press there.
  std::unique_ptr<MeshSurface> object_;
  double lift_mm_ = 0;
  // The table plane z_object = 0 in the press frame: z_object = n . p + d.
  Eigen::Vector3d table_normal_ = Eigen::Vector3d::UnitZ();
  double table_offset_mm_ = 0;
};

// The approach frame of a press along `direction` (need not be unit) whose
// line passes through `point_mm`: origin there, z against the direction (a
// touch target's base_from_approach, with the target at (0, 0)).
Eigen::Isometry3d approach_frame(const Eigen::Vector3d& point_mm, const Eigen::Vector3d& direction);

}  // namespace touchcloud::simulation
